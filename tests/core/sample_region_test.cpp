// What an analysis sample asks of a run (core/sample_region.hpp): the scattered grains (up to a
// distance, when given), the wall grains, and the grains and transfers that reach into the
// cylinder about the jet axis (3D z, 2D x), by their radius or their segment's length.
#include "core/sample_region.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace granjet {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The cylinder r <= 10 about the z axis, 1 <= z <= 6; scattered beyond 20.
SampleRegion cylinder() { return {.beyond = 20.0, .within = 10.0, .low = 1.0, .high = 6.0}; }

TEST(SampleRegion, HoldsTheGrainsThatOverlapTheCylinder) {
  const SampleRegion c = cylinder();
  const auto held = [&](Vec<3> x, double radius) {
    return c.holds_grain<3>(x, radius, GrainKind::kFree);
  };
  EXPECT_TRUE(held({0.0, 0.0, 3.0}, 0.5));
  EXPECT_TRUE(held({6.0, 8.0, 3.0}, 0.0));   // r = 10 exactly
  EXPECT_TRUE(held({6.0, 8.3, 3.0}, 0.5));   // r = 10.24, overlaps by 0.26
  EXPECT_FALSE(held({6.0, 8.7, 3.0}, 0.5));  // r = 10.57
  EXPECT_TRUE(held({0.0, 0.0, 0.6}, 0.5));   // below the bottom, overlapping it
  EXPECT_FALSE(held({0.0, 0.0, 0.4}, 0.5));
  EXPECT_TRUE(held({0.0, 0.0, 6.45}, 0.5));  // above the top
  EXPECT_FALSE(held({0.0, 0.0, 6.55}, 0.5));
  EXPECT_FALSE(held({3.0, 0.0, 30.0}, 0.5));  // high above the axis: neither in nor scattered
}

TEST(SampleRegion, HoldsScatteredWallAndNaNGrainsAnywhere) {
  const SampleRegion c = cylinder();
  EXPECT_TRUE(c.holds_grain<3>({0.0, 20.5, 40.0}, 0.5, GrainKind::kFree));
  EXPECT_FALSE(c.holds_grain<3>({0.0, 19.5, 40.0}, 0.5, GrainKind::kFree));
  EXPECT_TRUE(c.holds_grain<3>({0.0, 0.0, 40.0}, 0.5, GrainKind::kWall));
  EXPECT_TRUE(c.holds_grain<3>({kNaN, 0.0, 40.0}, 0.5, GrainKind::kFree));
  // Without a cylinder (outside the analysis window) only those.
  const SampleRegion scattered{.beyond = 20.0};
  EXPECT_FALSE(scattered.holds_grain<3>({0.0, 0.0, 3.0}, 0.5, GrainKind::kFree));
  EXPECT_TRUE(scattered.holds_grain<3>({0.0, 0.0, 3.0}, 0.5, GrainKind::kWall));
  EXPECT_TRUE(scattered.holds_grain<3>({0.0, 20.5, 3.0}, 0.5, GrainKind::kFree));
}

// A look that has seen every grain beyond 20 up to an earlier time asks only for the shell its
// grains can have crossed since (up to `until`); wall grains and the cylinder stay held.
TEST(SampleRegion, HoldsScatteredGrainsOnlyUpToUntil) {
  SampleRegion c = cylinder();
  c.until = 21.0;
  const auto held = [&](Vec<3> x, GrainKind kind = GrainKind::kFree) {
    return c.holds_grain<3>(x, 0.5, kind);
  };
  EXPECT_TRUE(held({0.0, 20.5, 40.0}));
  EXPECT_TRUE(held({0.0, 21.0, 40.0}));  // on the edge: the looker's own test decides
  EXPECT_FALSE(held({0.0, 21.5, 40.0}));
  EXPECT_FALSE(held({0.0, 19.5, 40.0}));
  EXPECT_TRUE(held({0.0, 30.0, 40.0}, GrainKind::kWall));
  EXPECT_TRUE(held({kNaN, 0.0, 40.0}));
  EXPECT_TRUE(held({0.0, 0.0, 3.0}));  // in the cylinder
}

// In 2D the jet axis is x, the "cylinder" the strip |y| <= within.
TEST(SampleRegion, TwoDimensionsCutAStripAboutTheXAxis) {
  const SampleRegion c = cylinder();
  EXPECT_TRUE(c.holds_grain<2>({3.0, -10.4}, 0.5, GrainKind::kFree));
  EXPECT_FALSE(c.holds_grain<2>({3.0, -10.6}, 0.5, GrainKind::kFree));
  EXPECT_FALSE(c.holds_grain<2>({7.0, 0.0}, 0.5, GrainKind::kFree));
  EXPECT_TRUE(c.holds_grain<2>({7.0, 20.5}, 0.5, GrainKind::kFree));
  EXPECT_TRUE(c.holds_transfer<2>({6.8, 0.0}, {5.9, 0.0}));
  EXPECT_FALSE(c.holds_transfer<2>({6.8, 0.0}, {6.1, 0.0}));
}

// A transfer reaches in by its segment: held when the segment may cross the cylinder, whichever
// end lies inside; one whose whole segment stays out is left out.
TEST(SampleRegion, HoldsTheTransfersWhoseSegmentMayReachIn) {
  const SampleRegion c = cylinder();
  EXPECT_TRUE(c.holds_transfer<3>({0.0, 0.0, 3.0}, {0.0, 1.0, 3.0}));     // inside
  EXPECT_TRUE(c.holds_transfer<3>({0.0, 10.8, 3.0}, {0.0, 9.9, 3.0}));    // from outside in
  EXPECT_TRUE(c.holds_transfer<3>({0.0, 0.0, 0.2}, {0.0, 0.0, 1.1}));     // up through the bottom
  EXPECT_FALSE(c.holds_transfer<3>({0.0, 10.8, 3.0}, {0.0, 11.5, 3.0}));  // out, moving away
  EXPECT_FALSE(c.holds_transfer<3>({0.0, 0.0, 7.2}, {0.0, 0.0, 8.0}));    // above the top
  EXPECT_FALSE(SampleRegion{}.holds_transfer<3>({0.0, 0.0, 3.0}, {0.0, 1.0, 3.0}));  // none
}

}  // namespace
}  // namespace granjet
