// Conformance: the 2D plate's edge on both backends (core/plate_face.hpp, soft_dem's plate
// contact, event_driven/plate.hpp). A grain passing beside a plate narrower than the jet (the
// HC runs at L/R < 1) meets the segment's end point: it is turned by it along the line from the
// point to its centre, [2.1] against an infinite mass.
#include <gtest/gtest.h>

#include "backends.hpp"
#include "core/plate_face.hpp"

namespace granjet {
namespace {

constexpr double kE = 0.75;
// binary.ini's gap: a soft contact starting exactly on a step biases AB2's e (plate_test.cpp).
constexpr double kGap = 0.0537;

template <class B>
Vec<2> after_flight(const Vec<2>& x, const Vec<2>& v, double t_end) {
  Scene s;
  s.kind = SceneKind::kJet;
  s.dimension = 2;
  s.wall.kind = WallKind::kPlate;
  s.wall.diameter = 10.0;  // end points at (kTargetSurface, +-5)
  s.contact.restitution = kE;
  s.contact.friction = 0.0;
  s.ed.restitution_law = RestitutionLaw::kConstant;
  Particles<2> p;
  p.add(0, GrainKind::kFree, x, v, 0.5, 1.0);
  auto sim = B::template make<2>(s, std::move(p));
  sim->advance_to(t_end);
  return sim->particles().velocity()[0];
}

template <class T>
class PlateRimConformance : public ::testing::Test {};
using TwoDimensional = ::testing::Types<testing::On<testing::SoftDemBackend, 2>,
                                        testing::On<testing::EventDrivenBackend, 2>>;
TYPED_TEST_SUITE(PlateRimConformance, TwoDimensional);

// Aimed at the end point along a 45 degree line from beside and in front: it comes back along
// the line with e times its speed and no sideways kick.
TYPED_TEST(PlateRimConformance, Eq2_1_AGrainAimedAtTheEdgeBouncesBackAlongTheLine) {
  using Backend = typename TypeParam::Backend;
  const Vec<2> edge(kTargetSurface, 5.0);
  const Vec<2> u = Vec<2>(1.0, 1.0).normalized();
  const Vec<2> v = after_flight<Backend>(edge + (0.5 + kGap) * u, -u, 0.6);
  EXPECT_NEAR(v.dot(u) / kE, 1.0, Backend::kRestitutionTolerance);
  EXPECT_NEAR(v.dot(Vec<2>(-u.y(), u.x())), 0.0, 1e-12);
}

// Just in front of the face plane but beside the edge, sliding in sideways: the edge turns it to
// the front; it neither lands deep in the face nor slips through.
TYPED_TEST(PlateRimConformance, AGrainSlidingInOverTheEdgeIsTurnedToTheFront) {
  using Backend = typename TypeParam::Backend;
  const Vec<2> v = after_flight<Backend>(Vec<2>(kTargetSurface + 0.2, 5.8), Vec<2>(0.0, -1.0), 1.0);
  EXPECT_GT(v.x(), 0.3);
  EXPECT_LT(v.norm(), 1.0);
}

}  // namespace
}  // namespace granjet
