// The measurement mesh (model §6): bin volumes and areas, half-cells, rotation of tensors to
// cylindrical components, grain shares and segment clipping [C.31]-[C.33] in both geometries.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/bin_grid.hpp"
#include "analysis/cartesian_layers.hpp"
#include "analysis/cylindrical_rings.hpp"
#include "analysis/segment_clip.hpp"

namespace granjet::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

// Heights from the target grains' top surface (height origin 0.5), as the positions below assume.
BinSpec jet3d_spec() { return {11.0, 0.5, 5, 1, 5.0}; }   // R_tar = 11: rings of 2.2
BinSpec jet2d_spec() { return {33.0, 0.5, 10, 2, 5.0}; }  // R_tar = 33: bins of 6.6

TEST(BinGeometry, RingVolumesAreAnnuliTimesHeightAndSumToTheCylinder) {
  const CylindricalRings rings(jet3d_spec());
  const BinGrid& g = rings.grid();
  ASSERT_EQ(g.size(), 5);
  double total = 0.0;
  for (int k = 0; k < 5; ++k) {
    // pi ((k+1)^2 - k^2) dr^2 dz, dr = 2.2, dz = 5.
    EXPECT_NEAR(rings.bin_volume(k), kPi * (2 * k + 1) * 2.2 * 2.2 * 5.0, 1e-12);
    total += rings.bin_volume(k);
  }
  EXPECT_NEAR(total, kPi * 11.0 * 11.0 * 5.0, 1e-10);
  // Centres r/R_tar = 0.1, 0.3, ..., 0.9 (model §6).
  EXPECT_NEAR(0.5 * (g.lateral_edge(2) + g.lateral_edge(3)) / 11.0, 0.5, 1e-15);
}

TEST(BinGeometry, LayerBinAreasAndIndices) {
  const CartesianLayers layers(jet2d_spec());
  const BinGrid& g = layers.grid();
  ASSERT_EQ(g.size(), 20);
  for (int b = 0; b < g.size(); ++b) EXPECT_NEAR(layers.bin_volume(b), 6.6 * 5.0, 1e-12);
  // Layer (a) is 0 < h <= 5 above the wall surface x = 0.5, layer (b) 5 < h <= 10.
  EXPECT_EQ(g.bin_at(layers.lateral({3.0, -32.0}), layers.height({3.0, -32.0})), 0);
  EXPECT_EQ(g.bin_at(layers.lateral({7.0, 32.0}), layers.height({7.0, 32.0})), 19);
  EXPECT_EQ(g.bin_at(0.1, -0.1), -1);  // below the wall surface
  EXPECT_EQ(g.bin_at(40.0, 1.0), -1);  // beyond R_tar
  EXPECT_EQ(layers.outward_sign(0), -1.0);
  EXPECT_EQ(layers.outward_sign(9), 1.0);
}

TEST(BinGeometry, HalfCellsCoverEachBinTwiceInEachDirection) {
  const BinGrid g(-33.0, 33.0, 10, 5.0, 2);
  // Bin (k, l) holds lateral half-cells 2k+1, 2k+2 and normal half-cells 2l, 2l+1.
  EXPECT_EQ(g.half_cell_at(-33.0 + 0.1, 0.1), g.half_cell(1, 0));
  EXPECT_EQ(g.half_cell_at(-33.0 + 3.4, 2.6), g.half_cell(2, 1));
  EXPECT_EQ(g.half_cell_at(-33.0 - 3.2, 9.9), g.half_cell(0, 3));  // half a bin beyond the edge
  EXPECT_EQ(g.half_cell_at(33.0 + 3.2, 9.9), g.half_cell(21, 3));
  EXPECT_EQ(g.half_cell_at(33.0 + 3.4, 1.0), -1);
}

// sigma_cyl = F sigma F^T with F's rows e_r, e_theta, e_z, checked component by component
// against the textbook transformation for an asymmetric tensor (contact stress with friction).
TEST(BinGeometry, RotationOfAKnownTensorToCylindricalComponents) {
  const CylindricalRings rings(jet3d_spec());
  Eigen::Matrix3d s;
  s << 1.0, 0.2, 0.3,  //
      -0.4, 2.0, 0.5,  //
      0.6, -0.7, 3.0;
  for (double theta : {0.0, 0.4, kPi / 2, 2.5, -1.2}) {
    const double c = std::cos(theta), n = std::sin(theta);
    const Eigen::Matrix3d f = rings.frame(Vec<3>(3.0 * c, 3.0 * n, 1.0));
    const Eigen::Matrix3d cyl = f * s * f.transpose();
    SCOPED_TRACE(theta);
    EXPECT_NEAR(cyl(0, 0), c * c * s(0, 0) + c * n * (s(0, 1) + s(1, 0)) + n * n * s(1, 1), 1e-14);
    EXPECT_NEAR(cyl(1, 1), n * n * s(0, 0) - c * n * (s(0, 1) + s(1, 0)) + c * c * s(1, 1), 1e-14);
    EXPECT_NEAR(cyl(0, 1), -c * n * s(0, 0) + c * c * s(0, 1) - n * n * s(1, 0) + c * n * s(1, 1),
                1e-14);
    EXPECT_NEAR(cyl(0, 2), c * s(0, 2) + n * s(1, 2), 1e-14);  // sigma_rz
    EXPECT_NEAR(cyl(2, 0), c * s(2, 0) + n * s(2, 1), 1e-14);  // sigma_zr
    EXPECT_NEAR(cyl(2, 2), s(2, 2), 1e-15);
    EXPECT_NEAR(cyl.trace(), s.trace(), 1e-14);  // the pressure does not depend on the axes
  }
  // On the y axis a radial stress diag(a, b, c) swaps: sigma_rr = b, sigma_tt = a.
  const Eigen::Matrix3d f = rings.frame(Vec<3>(0.0, 2.0, 1.0));
  const Eigen::Matrix3d d = f * Eigen::Vector3d(1, 2, 3).asDiagonal() * f.transpose();
  EXPECT_NEAR(d(0, 0), 2.0, 1e-15);
  EXPECT_NEAR(d(1, 1), 1.0, 1e-15);
}

template <class Coordinates>
std::map<int, double> shares(const Coordinates& c, const typename Coordinates::VecT& x, double r) {
  std::map<int, double> out;
  c.for_each_share(x, r, [&](int bin, double v) { out[bin] += v; });
  return out;
}

// A grain straddling ring and layer borders is shared so that its parts add up to the grain.
TEST(BinGeometry, SphereSharesOverRingsAndLayersSumToTheGrain) {
  BinSpec spec = jet3d_spec();
  spec.layers = 2;
  const CylindricalRings rings(spec);
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r = 0.5, grain = 4 * kPi / 3 * r * r * r;
  for (int trial = 0; trial < 200; ++trial) {
    // Centres near the ring borders 2.2 k and the layer border h = 5 (z = 5.5), inside the mesh.
    const double radius = 2.2 * (1 + trial % 4) + (u(rng) - 0.5);
    const double angle = 2 * kPi * u(rng), z = 5.5 + 2.0 * (u(rng) - 0.5);
    const auto s = shares(rings, Vec<3>(radius * std::cos(angle), radius * std::sin(angle), z), r);
    double sum = 0.0;
    for (const auto& [bin, v] : s) {
      EXPECT_GE(v, -1e-12);
      sum += v;
    }
    EXPECT_NEAR(sum, grain, 1e-9 * grain);
  }
  // Wholly inside a ring: one share, the whole grain.
  const auto inside = shares(rings, Vec<3>(3.3, 0.0, 3.0), r);
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_DOUBLE_EQ(inside.at(1), grain);
  // A grain across the axis lies in the first ring only.
  EXPECT_NEAR(shares(rings, Vec<3>(0.1, 0.0, 3.0), r).at(0), grain, 1e-12);
}

TEST(BinGeometry, DiskSharesOverLayerBinsSumToTheGrainAndSplitExactly) {
  const CartesianLayers layers(jet2d_spec());
  // Centred on the border y = 0 between bins 4 and 5 of layer (a): two exact halves.
  const auto half = shares(layers, Vec<2>(3.0, 0.0), 0.5);
  ASSERT_EQ(half.size(), 2u);
  EXPECT_NEAR(half.at(4), kPi / 8, 1e-14);
  EXPECT_NEAR(half.at(5), kPi / 8, 1e-14);
  // On the corner of four bins (y = 6.6, h = 5): four quarters.
  const auto quarters = shares(layers, Vec<2>(5.5, 6.6), 0.4);
  ASSERT_EQ(quarters.size(), 4u);
  for (const auto& [bin, v] : quarters) EXPECT_NEAR(v, kPi * 0.16 / 4, 1e-14);
}

// The fractions of a segment in each bin, by exact clipping [C.31]-[C.33].
template <class Coordinates>
std::map<int, double> pieces(const Coordinates& c, const typename Coordinates::VecT& a,
                             const typename Coordinates::VecT& b) {
  std::map<int, double> out;
  std::vector<double> scratch;
  clip_segment(c, a, b, scratch, [&](int bin, double s0, double s1) { out[bin] += s1 - s0; });
  return out;
}

TEST(BinGeometry, SegmentClippedAgainstLayerBins) {
  const CartesianLayers layers(jet2d_spec());
  // From y = -3 to y = 5 at h = 2 (x = 2.5): the border y = 0 splits it 3 : 5.
  auto p = pieces(layers, Vec<2>(2.5, -3.0), Vec<2>(2.5, 5.0));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_NEAR(p.at(4), 3.0 / 8.0, 1e-15);
  EXPECT_NEAR(p.at(5), 5.0 / 8.0, 1e-15);
  // Diagonal through the layer border h = 5 and out of the top h = 10: h from 3 to 13, y fixed.
  p = pieces(layers, Vec<2>(3.5, 1.0), Vec<2>(13.5, 1.0));
  EXPECT_NEAR(p.at(5), 0.2, 1e-15);
  EXPECT_NEAR(p.at(15), 0.5, 1e-15);
  EXPECT_EQ(p.size(), 2u);  // the rest is above the mesh
  EXPECT_TRUE(pieces(layers, Vec<2>(20.0, 1.0), Vec<2>(21.0, 1.0)).empty());
}

TEST(BinGeometry, SegmentClippedAgainstAnnulusSlab) {
  const CylindricalRings rings(jet3d_spec());
  // Radial, from r = 1 to r = 5 at h = 1.5: ring borders 2.2 and 4.4.
  auto p = pieces(rings, Vec<3>(1.0, 0.0, 2.0), Vec<3>(5.0, 0.0, 2.0));
  EXPECT_NEAR(p.at(0), 1.2 / 4.0, 1e-15);
  EXPECT_NEAR(p.at(1), 2.2 / 4.0, 1e-15);
  EXPECT_NEAR(p.at(2), 0.6 / 4.0, 1e-15);
  // A chord at x = 1.5 from y = -3 to y = 3 dips inside r = 2.2 for |y| < sqrt(2.2^2 - 1.5^2):
  // the annulus is not convex, and ring 1 gets the two outer stretches.
  const double dip = std::sqrt(2.2 * 2.2 - 1.5 * 1.5);
  p = pieces(rings, Vec<3>(1.5, -3.0, 2.0), Vec<3>(1.5, 3.0, 2.0));
  EXPECT_NEAR(p.at(0), 2 * dip / 6.0, 1e-14);
  EXPECT_NEAR(p.at(1), 1.0 - 2 * dip / 6.0, 1e-14);
  // Through the wall surface (z = 0.5): only the part above it counts.
  p = pieces(rings, Vec<3>(3.0, 0.0, 1.0), Vec<3>(3.0, 0.0, 0.0));
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NEAR(p.at(1), 0.5, 1e-15);
}

}  // namespace
}  // namespace granjet::analysis
