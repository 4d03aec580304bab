// The soft-DEM plate as a thin plate (core/plate_face.hpp): a grain meets the face point nearest
// its centre, on the face, its rim or (soft backend only) its back. The edge on both backends:
// tests/conformance/plate_rim_test.cpp.
#include <gtest/gtest.h>

#include "core/plate_face.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"

namespace granjet {
namespace {

constexpr double kE = 0.75;
// binary.ini's gap: a contact starting exactly on a step biases AB2's e (see the plate
// conformance test).
constexpr double kGap = 0.0537;

Scene plate_scene() {
  Scene s;
  s.kind = SceneKind::kJet;
  s.dimension = 2;
  s.wall.kind = WallKind::kPlate;
  s.wall.diameter = 10.0;  // rim at y = +-5, face at x = kTargetSurface
  s.contact.restitution = kE;
  s.contact.friction = 0.0;
  return s;
}

Vec<2> after_flight(const Vec<2>& x, const Vec<2>& v, double t_end) {
  Particles<2> p;
  p.add(0, GrainKind::kFree, x, v, 0.5, 1.0);
  dem::DemSimulator<2, dem::LinearSpringDashpot<2, false>> sim(plate_scene(), std::move(p));
  sim.advance_to(t_end);
  return sim.particles().velocity()[0];
}

// A grain that got behind the face meets its back: it comes off with e times its speed.
TEST(PlateRim, Eq2_1_TheBackOfTheFaceReflectsGrainsBehindIt) {
  const Vec<2> v = after_flight(Vec<2>(kTargetSurface - 0.5 - kGap, 0.0), Vec<2>(1.0, 0.0), 0.6);
  EXPECT_NEAR(v.x() / -kE, 1.0, 0.005);
}

TEST(PlateRim, NearestFacePointAndMirrorOverTheFaceAndBesideIt) {
  const PlateFace<3> face(10.0);
  const Vec<3> over(1.0, 2.0, 3.0), beside(6.0, 8.0, 2.0);
  EXPECT_EQ(face.nearest_point(over), Vec<3>(1.0, 2.0, kTargetSurface));
  EXPECT_EQ(face.mirror(over), Vec<3>(1.0, 2.0, 2.0 * kTargetSurface - 3.0));
  EXPECT_TRUE(face.nearest_point(beside).isApprox(Vec<3>(3.0, 4.0, kTargetSurface), 1e-15));
}

}  // namespace
}  // namespace granjet
