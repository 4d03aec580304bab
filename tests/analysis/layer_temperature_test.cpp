// FE.1's measure (analysis/layer_temperature.hpp): which grains layer (a) holds, and their T_g.
#include "analysis/layer_temperature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace granjet::analysis {
namespace {

Scene jet2d() {
  Scene s;
  s.dimension = 2;
  s.wall.diameter = 20.0;  // dy = R_tar / 5 = 2
  return s;
}

TEST(LayerTemperature, CountsTheFlowingGrainsOfLayerAAndTheirFluctuations) {
  Particles<2> p;
  // Inside: 0 < x <= 5 (from the centres' plane), -2 < y < 0. Velocities (1, 0) and (3, 2):
  // mean (2, 1), fluctuations (-1, -1) and (1, 1): T_g = (2 + 2) / (2 * 2) = 1.
  p.add(0, GrainKind::kFree, Vec<2>(1.0, -1.0), Vec<2>(1.0, 0.0), 0.5, 1.0);
  p.add(1, GrainKind::kFree, Vec<2>(4.9, -0.1), Vec<2>(3.0, 2.0), 0.5, 1.0);
  // Outside: beside the bin, above the layer, behind the origin, and a target grain.
  p.add(2, GrainKind::kFree, Vec<2>(2.0, 0.5), Vec<2>(9.0, 9.0), 0.5, 1.0);
  p.add(3, GrainKind::kFree, Vec<2>(5.5, -1.0), Vec<2>(9.0, 9.0), 0.5, 1.0);
  p.add(4, GrainKind::kFree, Vec<2>(-0.2, -1.0), Vec<2>(9.0, 9.0), 0.5, 1.0);
  p.add(5, GrainKind::kWall, Vec<2>(0.3, -1.0), Vec<2>(9.0, 9.0), 0.5, 1.0);
  const Scene s = jet2d();
  int count = 0;
  EXPECT_DOUBLE_EQ(layer_a_temperature(p, s, &count), 1.0);
  EXPECT_EQ(count, 2);
  // From the target grains' top surface the layer starts at x = 0.5 and ends at 5.5: grain 3
  // joins (its fluctuation about the new mean raises T_g).
  Scene surface = s;
  surface.analysis.height_origin = HeightOrigin::kWallSurface;
  EXPECT_GT(layer_a_temperature(p, surface, &count), 1.0);
  EXPECT_EQ(count, 3);
}

TEST(LayerTemperature, FewerThanTwoGrainsMeasureNothing) {
  Particles<2> p;
  p.add(0, GrainKind::kFree, Vec<2>(1.0, -1.0), Vec<2>(1.0, 0.0), 0.5, 1.0);
  EXPECT_TRUE(std::isnan(layer_a_temperature(p, jet2d())));
}

}  // namespace
}  // namespace granjet::analysis
