// Pair prediction [model §8]: the contact time of two grains in free flight, robust at grazing
// incidence and for touching or overlapping grains.
#include "event_driven/flight.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace granjet::ed {
namespace {

using V = Vec<3>;

double contact_delay(const V& dr, const V& dv, double sigma) {
  const PairQuadratic q = pair_quadratic(dr, dv, sigma);
  return ed::contact_delay(q.b, q.c, q.a);
}

TEST(ContactDelay, HeadOnApproachTouchesAfterTheGapOverTheSpeed) {
  // 0.5 apart at the surfaces, closing at 2: contact after 0.25.
  EXPECT_DOUBLE_EQ(contact_delay(V(1.5, 0, 0), V(-2, 0, 0), 1.0), 0.25);
}

TEST(ContactDelay, RecedingOrPassingPairsNeverTouch) {
  EXPECT_EQ(contact_delay(V(1.5, 0, 0), V(2, 0, 0), 1.0), kNever);
  EXPECT_EQ(contact_delay(V(1.5, 0, 0), V(0, 1, 0), 1.0), kNever);   // perpendicular: b = 0
  EXPECT_EQ(contact_delay(V(3, 1.5, 0), V(-1, 0, 0), 1.0), kNever);  // misses by 0.5
  EXPECT_EQ(contact_delay(V(3, 1.0, 0), V(-1, 0, 0), 1.0), kNever);  // exactly tangent
}

TEST(ContactDelay, TouchingOrOverlappingPairsCollideAtOnceOnlyWhenApproaching) {
  EXPECT_EQ(contact_delay(V(1, 0, 0), V(-1, 0, 0), 1.0), 0.0);
  EXPECT_EQ(contact_delay(V(0.9, 0, 0), V(-1, 0.3, 0), 1.0), 0.0);
  EXPECT_EQ(contact_delay(V(1, 0, 0), V(1, 0, 0), 1.0), kNever);
  EXPECT_EQ(contact_delay(V(0.9, 0, 0), V(0.01, 5, 0), 1.0), kNever);
}

// Near contact on approach, a c << b^2: the textbook root (-b - sqrt(b^2 - a c))/a cancels to a
// few percent here; the form used keeps full precision. The gap 2^-47 is exact in binary.
TEST(ContactDelay, NearContactApproachKeepsFullPrecision) {
  const double gap = std::ldexp(1.0, -47);
  const double expected = gap / 3.0;
  EXPECT_NEAR(contact_delay(V(1.0 + gap, 0, 0), V(-3, 0, 0), 1.0), expected, 1e-12 * expected);
  EXPECT_NEAR(contact_delay(V(0, 1.0 + gap, 0), V(0, -1.5, 0), 1.0), 2.0 * expected,
              1e-12 * expected);
}

// Grazing incidence: a lateral offset just inside sigma collides, just outside misses. The
// contact x^2 + y^2 = 1 at t = 10 - x; near tangency t is ill-conditioned in the inputs
// (dt/dy ~ 1/x), hence the absolute tolerance.
TEST(ContactDelay, GrazingIncidenceNeitherMissesNorInvents) {
  const double inside = 1.0 - 1e-12, outside = 1.0 + 1e-12;
  const double x_contact = std::sqrt((1.0 - inside) * (1.0 + inside));
  EXPECT_NEAR(contact_delay(V(10, inside, 0), V(-1, 0, 0), 1.0), 10.0 - x_contact, 1e-8);
  EXPECT_EQ(contact_delay(V(10, outside, 0), V(-1, 0, 0), 1.0), kNever);
}

TEST(Flight, StreamingMovesAlongTheVelocityFromTheGrainsOwnTime) {
  Flight<2> f;
  f.x = Vec<2>(1, 2);
  f.t = 3.0;
  f.v = Vec<2>(0.5, -1);
  EXPECT_EQ(f.position_at(5.0), Vec<2>(2, 0));
  f.stream_to(5.0);
  EXPECT_EQ(f.x, Vec<2>(2, 0));
  EXPECT_EQ(f.t, 5.0);
}

}  // namespace
}  // namespace granjet::ed
