// The restitution laws of the event-driven backend [model §8].
#include "event_driven/restitution.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "event_driven/flight.hpp"

namespace granjet::ed {
namespace {

Scene law(RestitutionLaw kind) {
  Scene s;
  s.contact.restitution = 0.75;
  s.ed.restitution_law = kind;
  s.ed.v0 = 0.1;
  s.ed.tc = 0.1;
  return s;
}

TEST(Restitution, ConstantIsE0Always) {
  const Restitution e(law(RestitutionLaw::kConstant));
  EXPECT_EQ(e(1e-9, 0.0, 0.0), 0.75);
  EXPECT_EQ(e(10.0, kNever, kNever), 0.75);
}

TEST(Restitution, VelocityDependentFollowsTheLawBelowV0AndIsE0Above) {
  const Restitution e(law(RestitutionLaw::kVelocityDependent));
  EXPECT_EQ(e(0.5, kNever, kNever), 0.75);
  EXPECT_EQ(e(0.1, kNever, kNever), 0.75);  // continuous at v0
  EXPECT_DOUBLE_EQ(e(0.05, kNever, kNever), 1.0 - 0.25 * std::pow(0.5, 0.75));
  EXPECT_NEAR(e(1e-12, kNever, kNever), 1.0, 1e-8);  // slow collisions nearly elastic
  EXPECT_LT(e(0.01, kNever, kNever), e(0.001, kNever, kNever));
}

TEST(Restitution, TcModelIsElasticWhenEitherGrainCollidedLessThanTcAgo) {
  const Restitution e(law(RestitutionLaw::kTcModel));
  EXPECT_EQ(e(1.0, 0.05, kNever), 1.0);
  EXPECT_EQ(e(1.0, kNever, 0.0999), 1.0);
  EXPECT_EQ(e(1.0, 0.1, 0.2), 0.75);
  EXPECT_EQ(e(1.0, kNever, kNever), 0.75);
}

}  // namespace
}  // namespace granjet::ed
