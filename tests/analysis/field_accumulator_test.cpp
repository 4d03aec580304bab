// Fields per bin from synthetic data with known answers (model §6): contact stress of a lattice
// with known pair forces straddling bin borders [C.31]-[C.33]; kinetic stress of a Maxwellian
// = n T I; strain rate of a linear shear field; binned mass and volume sum to the totals; the
// contact stress split by contact type (wall) and direction (normal), fabric and contact density.
#include "analysis/field_accumulator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <numbers>
#include <numeric>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/exact_sum.hpp"
#include "core/jet_geometry.hpp"
#include "core/plate_face.hpp"
#include "core/sample_region.hpp"
#include "core/state_archive.hpp"

namespace granjet::analysis {
namespace {

constexpr double kPi = std::numbers::pi;

// Heights from the target grains' top surface (origin 0.5): the lattices below keep their first
// row 0.3 d above it. The tests hold for any origin; this one keeps them as written.
BinSpec jet3d_spec() { return {11.0, 0.5, 5, 1, 5.0}; }
BinSpec jet2d_spec() { return {33.0, 0.5, 10, 2, 5.0}; }

// A uniformly random point of the 3D mesh region (r < R, 0 < h < top) or the 2D one, kept
// `margin` away from its outer surfaces.
template <int D>
Vec<D> random_point(std::mt19937_64& rng, const BinSpec& s, double margin) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = margin + (s.layers * s.layer_height - 2 * margin) * u(rng) + s.height_origin;
  if constexpr (D == 3) {
    const double r = (s.target_radius - margin) * std::sqrt(u(rng)), a = 2 * kPi * u(rng);
    return {r * std::cos(a), r * std::sin(a), h};
  } else {
    return {h, (s.target_radius - margin) * (2 * u(rng) - 1)};
  }
}

// Grains of a square (2D) or simple cubic (3D) lattice of spacing 1 filling the mesh region,
// each pair of nearest neighbours pushing with a known impulse J = f(midpoint) (r_i - r_j),
// f varying in space so that bins differ. Many bonds straddle bin borders.
template <int D>
std::vector<PairImpulse<D>> lattice_bonds(const BinSpec& s) {
  std::vector<Vec<D>> sites;
  const int n_h = static_cast<int>(s.layers * s.layer_height) - 1;
  const int n_l = static_cast<int>(s.target_radius) - 1;
  for (int k = 0; k < n_h; ++k)
    for (int i = -n_l; i <= n_l; ++i)
      for (int j = (D == 3 ? -n_l : 0); j <= (D == 3 ? n_l : 0); ++j) {
        Vec<D> x;
        if constexpr (D == 3) {
          x = {i + 0.25, j + 0.35, k + 1.0 + s.height_origin - 0.2};
          if (std::hypot(x[0], x[1]) > s.target_radius - 1.0) continue;
        } else {
          x = {k + 1.0 + s.height_origin - 0.2, i + 0.35};
        }
        sites.push_back(x);
      }
  std::vector<PairImpulse<D>> bonds;
  for (std::size_t a = 0; a < sites.size(); ++a)
    for (std::size_t b = a + 1; b < sites.size(); ++b) {
      const Vec<D> r = sites[a] - sites[b];
      if (r.norm() > 1.01) continue;
      const Vec<D> mid = 0.5 * (sites[a] + sites[b]);
      const double f = 1.0 + 0.1 * mid.sum() + 0.01 * mid.squaredNorm();
      bonds.push_back({GrainId(a), GrainId(b), sites[a], sites[b], f * r});
    }
  return bonds;
}

template <class T>
class FieldAccumulatorTyped : public ::testing::Test {};
using Dimensions = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(FieldAccumulatorTyped, Dimensions);

BinSpec spec_for(int dimension) { return dimension == 3 ? jet3d_spec() : jet2d_spec(); }

// [C.31]-[C.33]: every bond lies inside the mesh, so the bins' contact stresses times their
// volumes and the transfer time add up to the total virial sum J r^T: in Cartesian components
// ("stress_xyz" in 3D; without grains the stress is the contact part alone), and in the local
// frame for the trace, which the per-transfer rotation leaves unchanged.
TYPED_TEST(FieldAccumulatorTyped, EqC31_C33_LatticeContactStressSumsToTheVirial) {
  constexpr int D = TypeParam::value;
  using Coordinates = typename FieldAccumulator<D>::Coordinates;
  const BinSpec spec = spec_for(D);
  const auto bonds = lattice_bonds<D>(spec);
  ASSERT_GT(bonds.size(), 1000u);
  Eigen::Matrix<double, D, D> virial = Eigen::Matrix<double, D, D>::Zero();
  for (const auto& t : bonds) virial += t.impulse * (t.position_i - t.position_j).transpose();

  FieldAccumulator<D> acc(spec);
  const double tau = 0.25;
  acc.sample(Particles<D>{}, {}, 0.0);
  acc.sample(Particles<D>{}, bonds, tau);
  const Table f = acc.fields({});
  const Table layout = acc.layout();
  const std::string cartesian = D == 3 ? "stress_xyz." : "stress.";
  Eigen::Matrix<double, D, D> xyz = Eigen::Matrix<double, D, D>::Zero();
  double trace = 0.0;
  for (std::size_t bin = 0; bin < f.rows(); ++bin) {
    const double weight = layout.at(bin, "volume") * tau;
    for (int a = 0; a < D; ++a) {
      const std::string local(Coordinates::kAxes[a]);
      trace += weight * f.at(bin, "stress_contact." + local + local);
      for (int b = 0; b < D; ++b)
        xyz(a, b) += weight * f.at(bin, cartesian + std::string(Coordinates::kCartesianAxes[a]) +
                                            std::string(Coordinates::kCartesianAxes[b]));
    }
  }
  EXPECT_NEAR(trace, virial.trace(), 1e-12 * std::abs(virial.trace()));
  EXPECT_LT((xyz - virial).norm(), 1e-12 * virial.norm());
  // The lattice is not uniform in the bins: their stresses differ, so a wrong split would show.
  EXPECT_GT(std::abs(f.at(0, "P") - f.at(1, "P")), 1e-3 * std::abs(f.at(0, "P")));
}

// One bond across a border splits exactly by the lengths on either side: 0.3 and 0.7.
TEST(FieldAccumulator, EqC31_C33_BondAcrossABorderSplitsByLength) {
  FieldAccumulator<2> acc(jet2d_spec());
  const Vec<2> xi(3.0, -0.3), xj(3.0, 0.7), impulse(0.0, -2.0);  // pushes i away from j
  acc.sample(Particles<2>{}, {}, 0.0);
  const std::vector<PairImpulse<2>> bond{{0, 1, xi, xj, impulse}};
  acc.sample(Particles<2>{}, bond, 0.5);
  const Table f = acc.fields({});
  const double v = 6.6 * 5.0, j_r = -2.0 * -1.0;  // J_y r_y, r = r_i - r_j = (0, -1)
  EXPECT_NEAR(f.at(4, "stress_contact.yy"), 0.3 * j_r / (v * 0.5), 1e-15);
  EXPECT_NEAR(f.at(5, "stress_contact.yy"), 0.7 * j_r / (v * 0.5), 1e-15);
  EXPECT_EQ(f.at(4, "stress_contact.xx"), 0.0);
  EXPECT_EQ(f.at(6, "stress_contact.yy"), 0.0);
}

// Each transfer is rotated to the cylindrical frame where it acts: a radial bond on the y axis is
// pure sigma_rr, a tangential one on the x axis pure sigma_tt, though in Cartesian axes they are
// sigma_yy and sigma_yy again.
TEST(FieldAccumulator, EqC31_C33_RingContactStressInTheLocalFrame) {
  FieldAccumulator<3> acc(jet3d_spec());
  acc.sample(Particles<3>{}, {}, 0.0);
  const std::vector<PairImpulse<3>> bonds{
      {0, 1, {0.0, 5.0, 2.0}, {0.0, 6.0, 2.0}, {0.0, -2.0, 0.0}},    // radial, ring 2
      {2, 3, {5.0, -0.5, 2.0}, {5.0, 0.5, 2.0}, {0.0, -3.0, 0.0}}};  // tangential, ring 2
  acc.sample(Particles<3>{}, bonds, 1.0);
  const Table f = acc.fields({});
  const double v = acc.layout().at(2, "volume");
  EXPECT_NEAR(f.at(2, "stress_contact.rr") * v, 2.0, 1e-12);
  // Lying wholly in one ring, each bond is rotated with the frame at its middle.
  EXPECT_NEAR(f.at(2, "stress_contact.tt") * v, 3.0, 1e-12);
  EXPECT_NEAR(f.at(2, "stress_contact.rt") * v, 0.0, 1e-12);
  EXPECT_NEAR(f.at(2, "stress_xyz.yy") * v, 5.0, 1e-12);
  EXPECT_EQ(f.at(2, "stress_contact.zz"), 0.0);
}

// The two backends' currencies give the same contact stress for the same momentum flow: soft
// DEM hands a steady force F as F x elapsed at every sample, ED the individual impulses summing
// to F tau, arriving unevenly between samples. Both: sum(J r^T A)/(V tau).
TEST(FieldAccumulator, EqC31_C33_DemForceSamplesAndEdImpulsesAgree) {
  const Vec<2> xi(3.0, 1.2), xj(3.8, 2.0), force(-0.3, -0.4);
  const auto bond = [&](double scale) {
    return std::vector<PairImpulse<2>>{{0, 1, xi, xj, scale * force}};
  };
  FieldAccumulator<2> dem(jet2d_spec()), ed(jet2d_spec());
  dem.sample(Particles<2>{}, {}, 0.0);
  for (int k = 0; k < 8; ++k) dem.sample(Particles<2>{}, bond(0.25), 0.25);  // tau = 2
  ed.sample(Particles<2>{}, {}, 0.0);
  std::vector<PairImpulse<2>> burst;
  for (int k = 0; k < 5; ++k) burst.push_back(bond(0.3).front());  // 1.5 F in the first second
  ed.sample(Particles<2>{}, burst, 1.0);
  ed.sample(Particles<2>{}, bond(0.5), 1.0);  // 0.5 F in the second
  const Table a = dem.fields({}), b = ed.fields({});
  EXPECT_NEAR(a.at(5, "stress_contact.xy"), b.at(5, "stress_contact.xy"), 1e-15);
  EXPECT_NEAR(a.at(5, "P"), b.at(5, "P"), 1e-15);
  // F r^T / V with r = r_i - r_j = (-0.8, -0.8): sigma_xy = F_x r_y / V.
  EXPECT_NEAR(a.at(5, "stress_contact.xy"), -0.3 * -0.8 / (6.6 * 5.0), 1e-15);
}

// A Maxwellian at temperature T on top of a mean flow (radial outflow in 3D): the kinetic stress
// in the local frame is n T I, T_g = T_alpha = T, whatever the mean flow. The statistical error
// of a diagonal component is sqrt(2/N) relative (N ~ 10^4 grain samples per bin: 1.4%), of an
// off-diagonal one n T/sqrt(N); the tolerances are 5 of those.
TYPED_TEST(FieldAccumulatorTyped, MaxwellianKineticStressIsNTIdentity) {
  constexpr int D = TypeParam::value;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> acc(spec);
  std::mt19937_64 rng(41);
  const double temperature = 0.04, mass = 1.0;
  std::normal_distribution<double> gauss(0.0, std::sqrt(temperature / mass));
  const int grains = D == 3 ? 10000 : 40000, snapshots = 5;
  for (int s = 0; s < snapshots; ++s) {
    Particles<D> p;
    for (int i = 0; i < grains; ++i) {
      const Vec<D> x = random_point<D>(rng, spec, 0.0);
      Vec<D> v;
      for (int a = 0; a < D; ++a) v[a] = gauss(rng);
      if constexpr (D == 3)
        v += 0.5 * Vec<3>(x.x(), x.y(), 0.0).normalized() - Vec<3>(0, 0, 0.3);
      else
        v += Vec<2>(-0.3, x.y() > 0 ? 0.5 : -0.5);
      p.add(i, GrainKind::kFree, x, v, 0.05, mass);
    }
    acc.sample(p, {}, 0.0);
  }
  const Table f = acc.fields({});
  const auto& axes = FieldAccumulator<D>::Coordinates::kAxes;
  for (std::size_t bin = 0; bin < f.rows(); ++bin) {
    SCOPED_TRACE(bin);
    const double n = f.at(bin, "n");
    const double count = n * acc.layout().at(bin, "volume") * snapshots;
    ASSERT_GT(count, 2000.0);
    const double diag_tol = 5.0 * std::sqrt(2.0 / count), off_tol = 5.0 / std::sqrt(count);
    EXPECT_NEAR(f.at(bin, "T_g") / temperature, 1.0, diag_tol);
    for (int a = 0; a < D; ++a) {
      const std::string ax(axes[a]);
      EXPECT_NEAR(f.at(bin, "T_alpha." + ax) / temperature, 1.0, diag_tol);
      for (int b = 0; b < D; ++b) {
        const double s =
            f.at(bin, "stress_kinetic." + ax + std::string(axes[b])) / (n * temperature);
        EXPECT_NEAR(s, a == b ? 1.0 : 0.0, a == b ? diag_tol : off_tol);
      }
    }
    // The mean flow itself is measured, not counted as temperature.
    if constexpr (D == 3) {
      EXPECT_NEAR(f.at(bin, "v.r"), 0.5, 0.01);
      EXPECT_NEAR(f.at(bin, "v.z"), -0.3, 0.01);
    }
    // Without transfers there is no contact information.
    EXPECT_TRUE(
        std::isnan(f.at(bin, "stress_contact." + std::string(axes[0]) + std::string(axes[0]))));
  }
}

// A linear velocity field v_lat = g h, v_h = k lat (3D: v_r = g h, v_z = k r; 2D: v_y = g h,
// v_x = k y) has the shear rate (g + k)/2 exactly, wherever the grains are: the half-bin
// differences are divided by the mean positions' differences.
TYPED_TEST(FieldAccumulatorTyped, LinearShearFieldGivesItsStrainRate) {
  constexpr int D = TypeParam::value;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> acc(spec);
  std::mt19937_64 rng(51);
  const double g = 0.3, k = -0.08;
  Particles<D> p;
  BinSpec wide = spec;  // grains also half a bin beyond the lateral ends
  wide.target_radius += 0.5 * spec.target_radius / 5;  // half a bin width (R_tar/5)
  for (int i = 0; i < 20000; ++i) {
    const Vec<D> x = random_point<D>(rng, wide, 0.0);
    Vec<D> v;
    if constexpr (D == 3) {
      const double r = std::hypot(x[0], x[1]);
      v << g * (x.z() - 0.5) * x.x() / r, g * (x.z() - 0.5) * x.y() / r, k * r;
    } else {
      v << k * x.y(), g * (x.x() - 0.5);
    }
    p.add(i, GrainKind::kFree, x, v, 0.05, 1.0);
  }
  acc.sample(p, {}, 0.0);
  const Table f = acc.fields({});
  for (std::size_t bin = 0; bin < f.rows(); ++bin)
    EXPECT_NEAR(f.at(bin, "D"), 0.5 * (g + k), 1e-10) << "bin " << bin;
}

// Every grain inside the mesh: the bins' n V add up to the grain count and phi V to the grains'
// total volume (exact shares, not centre counting), however the grains straddle the borders.
TYPED_TEST(FieldAccumulatorTyped, BinnedCountAndVolumeSumToTheTotals) {
  constexpr int D = TypeParam::value;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> acc(spec);
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<double> radius(0.4, 0.5);
  Particles<D> p;
  double volume = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const double r = radius(rng);
    p.add(i, GrainKind::kFree, random_point<D>(rng, spec, 0.5), Vec<D>::Zero(), r, 1.0 + i % 3);
    volume += Dim<D>::volume(r);
  }
  // A wall grain is not part of the flow.
  p.add(9999, GrainKind::kWall, random_point<D>(rng, spec, 0.5), Vec<D>::Zero(), 0.5, 1.0);
  acc.sample(p, {}, 0.0);
  acc.sample(p, {}, 0.0);  // two snapshots: the averages are per snapshot
  const Table f = acc.fields({});
  const Table layout = acc.layout();
  double count = 0.0, grain_volume = 0.0;
  for (std::size_t bin = 0; bin < f.rows(); ++bin) {
    count += f.at(bin, "n") * layout.at(bin, "volume");
    grain_volume += f.at(bin, "phi") * layout.at(bin, "volume");
  }
  EXPECT_NEAR(count, 3000.0, 1e-9);
  EXPECT_NEAR(grain_volume, volume, 1e-8 * volume);
}

// --- The contact stress split by contact type and direction, fabric, contact density ---------

// The 2D mesh's bin 5 is 0 < y < 6.6, 0 < h < 5 (x from 0.5 to 5.5): V = 33.
constexpr double kBin5Volume = 6.6 * 5.0;

Particles<2> grains(std::initializer_list<std::pair<GrainId, GrainKind>> list) {
  Particles<2> p;
  for (const auto& [id, kind] : list)
    p.add(id, kind, Vec<2>(10.0 + id, 40.0), Vec<2>::Zero(), 0.5, 1.0);  // outside the mesh
  return p;
}

template <class Matrix>
void expect_tensor(const Table& f, std::size_t bin, const std::string& name, const Matrix& expected,
                   double tol) {
  const auto& axes = FieldAccumulator<Matrix::RowsAtCompileTime>::Coordinates::kAxes;
  for (int a = 0; a < expected.rows(); ++a)
    for (int b = 0; b < expected.cols(); ++b) {
      const std::string column = name + "." + std::string(axes[a]) + std::string(axes[b]);
      EXPECT_NEAR(f.at(bin, column), expected(a, b), tol) << column << " in bin " << bin;
    }
}

void expect_same_tensor(const Table& f, std::size_t bin, const std::string& a, const std::string& b,
                        std::string_view axes) {
  for (char x : axes)
    for (char y : axes) {
      const std::string ab{'.', x, y};
      EXPECT_EQ(f.at(bin, a + ab), f.at(bin, b + ab)) << a << ab << " in bin " << bin;
    }
}

// A transfer between a flowing grain and a target grain is all wall part; one between two
// flowing grains has none. The wall grain (id 7) is known from the first snapshot and counts as
// wall even when gone from the later one; id 12, beyond every wall id, is a flowing grain.
TEST(FieldAccumulator, WallPartIsTheTransfersWithATargetGrain) {
  FieldAccumulator<2> acc(jet2d_spec());
  acc.sample(grains({{0, GrainKind::kFree}, {7, GrainKind::kWall}, {12, GrainKind::kFree}}), {},
             0.0);
  const Vec<2> impulse(0.5, -0.2);
  const std::vector<PairImpulse<2>> transfers{
      {0, 7, {3.0, 2.0}, {2.2, 2.6}, impulse},    // flowing-wall, bin 5
      {12, 0, {3.0, 8.0}, {2.2, 8.6}, impulse}};  // flowing-flowing, bin 6
  acc.sample(grains({{0, GrainKind::kFree}, {12, GrainKind::kFree}}), transfers, 0.5);
  const Table f = acc.fields({});
  expect_same_tensor(f, 5, "stress_contact_wall", "stress_contact", "xy");
  // J r^T / (V tau), r = r_i - r_j = (0.8, -0.6).
  Eigen::Matrix2d expected;
  expected << 0.5 * 0.8, 0.5 * -0.6, -0.2 * 0.8, -0.2 * -0.6;
  expect_tensor(f, 5, "stress_contact", expected / (kBin5Volume * 0.5), 1e-15);
  expect_tensor(f, 6, "stress_contact", expected / (kBin5Volume * 0.5), 1e-15);
  expect_tensor(f, 6, "stress_contact_wall", Eigen::Matrix2d::Zero(), 0.0);
}

// analysis.stress_wall_contacts = exclude: the same two transfers, and the contact stress keeps
// the flowing-flowing one only; the wall part is still reported, and P follows the choice.
TEST(FieldAccumulator, ExcludingWallContactsLeavesTheFlowingGrainsOwnStress) {
  FieldAccumulator<2> acc(jet2d_spec());
  acc.sample(grains({{0, GrainKind::kFree}, {7, GrainKind::kWall}, {12, GrainKind::kFree}}), {},
             0.0);
  const Vec<2> impulse(0.5, -0.2);
  const std::vector<PairImpulse<2>> transfers{{0, 7, {3.0, 2.0}, {2.2, 2.6}, impulse},
                                              {12, 0, {3.0, 8.0}, {2.2, 8.6}, impulse}};
  acc.sample(grains({{0, GrainKind::kFree}, {12, GrainKind::kFree}}), transfers, 0.5);
  FieldOptions without;
  without.wall_contacts = false;
  const Table all = acc.fields({}), own = acc.fields(without);
  Eigen::Matrix2d expected;
  expected << 0.5 * 0.8, 0.5 * -0.6, -0.2 * 0.8, -0.2 * -0.6;
  expect_tensor(own, 5, "stress_contact", Eigen::Matrix2d::Zero(), 0.0);
  expect_tensor(own, 5, "stress_contact_wall", expected / (kBin5Volume * 0.5), 1e-15);
  expect_tensor(own, 6, "stress_contact", expected / (kBin5Volume * 0.5), 1e-15);
  EXPECT_NEAR(all.at(5, "P") - own.at(5, "P"), expected.trace() / 2 / (kBin5Volume * 0.5), 1e-15);
  EXPECT_EQ(all.at(6, "P"), own.at(6, "P"));
}

// The normal part of an impulse is (J.n) n r^T with n along the line of centres; the rest is
// tangential. J = (1, 0.5), r = (0.45, -0.6), |r| = 0.75, n = (0.6, -0.8): J.n = 0.2.
TEST(FieldAccumulator, NormalPartIsTheImpulseAlongTheLineOfCentres) {
  FieldAccumulator<2> acc(jet2d_spec());
  acc.sample(Particles<2>{}, {}, 0.0);
  const std::vector<PairImpulse<2>> transfer{{0, 1, {3.0, 2.0}, {2.55, 2.6}, {1.0, 0.5}}};
  const double tau = 0.5;
  acc.sample(Particles<2>{}, transfer, tau);
  const Table f = acc.fields({});
  const double scale = 1.0 / (kBin5Volume * tau);
  Eigen::Matrix2d normal, tangential;  // J_n r^T with J_n = (0.12, -0.16); J_t = (0.88, 0.66)
  normal << 0.12 * 0.45, 0.12 * -0.6, -0.16 * 0.45, -0.16 * -0.6;
  tangential << 0.88 * 0.45, 0.88 * -0.6, 0.66 * 0.45, 0.66 * -0.6;
  expect_tensor(f, 5, "stress_contact_normal", normal * scale, 1e-15);
  for (const char* ab : {"xx", "xy", "yx", "yy"}) {
    const std::string c(ab);
    EXPECT_NEAR(f.at(5, "stress_contact." + c) - f.at(5, "stress_contact_normal." + c),
                tangential(c[0] - 'x', c[1] - 'x') * scale, 1e-15)
        << c;
  }
  // No wall grain: no wall part.
  expect_tensor(f, 5, "stress_contact_wall", Eigen::Matrix2d::Zero(), 0.0);
}

// Two contacts of equal weight along x and along y: fabric diag(1/2, 1/2). The contact density
// counts the segment fractions per sample that covers time (here 2 of 3) and per unit volume;
// a bond across a border counts by its fractions (0.3 in bin 6, 0.7 in bin 7).
TEST(FieldAccumulator, FabricAndContactDensity) {
  FieldAccumulator<2> acc(jet2d_spec());
  acc.sample(Particles<2>{}, {}, 0.0);
  const std::vector<PairImpulse<2>> transfers{
      {0, 1, {2.0, 3.0}, {3.0, 3.0}, {-0.1, 0.0}},    // along x, bin 5
      {2, 3, {4.0, 2.0}, {4.0, 3.0}, {0.0, -0.3}},    // along y, bin 5
      {4, 5, {3.0, 12.9}, {3.0, 13.9}, {0.0, 0.2}}};  // along y, across y = 13.2
  acc.sample(Particles<2>{}, transfers, 0.25);
  acc.sample(Particles<2>{}, transfers, 0.25);
  const Table f = acc.fields({});
  expect_tensor(f, 5, "fabric", Eigen::Matrix2d(Eigen::Vector2d(0.5, 0.5).asDiagonal()), 1e-15);
  EXPECT_NEAR(f.at(5, "contact_density"), 4.0 / (2 * kBin5Volume), 1e-15);
  EXPECT_NEAR(f.at(6, "contact_density"), 2 * 0.3 / (2 * kBin5Volume), 1e-14);
  EXPECT_NEAR(f.at(7, "contact_density"), 2 * 0.7 / (2 * kBin5Volume), 1e-14);
  expect_tensor(f, 6, "fabric", Eigen::Matrix2d(Eigen::Vector2d(0.0, 1.0).asDiagonal()), 1e-15);
  // A bin without transfers: no contacts, and no fabric to speak of.
  EXPECT_EQ(f.at(0, "contact_density"), 0.0);
  EXPECT_TRUE(std::isnan(f.at(0, "fabric.xx")));

  // Without transfer time (stored frames) nothing of the contacts is known.
  FieldAccumulator<2> frames(jet2d_spec());
  frames.sample(Particles<2>{}, {}, 0.0);
  const Table g = frames.fields({});
  EXPECT_TRUE(std::isnan(g.at(5, "contact_density")));
  EXPECT_TRUE(std::isnan(g.at(5, "stress_contact_wall.xy")));
  EXPECT_TRUE(std::isnan(g.at(5, "stress_contact_normal.xy")));
}

// The flat plate is partner kPlateId, at the grain's mirror image: a wall contact. With the
// layers starting at the face (origin 0.5, as in jet2d_spec) half of the segment, the grain's
// half, lies in the mesh.
TEST(FieldAccumulator, PlateTransfersAreWallTransfers) {
  FieldAccumulator<2> acc(jet2d_spec());
  acc.sample(grains({{0, GrainKind::kFree}}), {}, 0.0);
  const Vec<2> x(1.0, 2.0), image(0.0, 2.0);  // face at x = 0.5
  const Vec<2> impulse(0.4, 0.1);             // pushed off the face, with some friction
  acc.sample(grains({{0, GrainKind::kFree}}),
             std::vector<PairImpulse<2>>{{0, kPlateId, x, image, impulse}}, 1.0);
  const Table f = acc.fields({});
  expect_same_tensor(f, 5, "stress_contact_wall", "stress_contact", "xy");
  Eigen::Matrix2d expected;  // 0.5 J r^T / V, r = (1, 0)
  expected << 0.4, 0.0, 0.1, 0.0;
  expect_tensor(f, 5, "stress_contact_wall", 0.5 * expected / kBin5Volume, 1e-15);
  expect_tensor(f, 5, "stress_contact_normal",
                Eigen::Matrix2d(Eigen::Vector2d(0.5 * 0.4 / kBin5Volume, 0.0).asDiagonal()), 1e-15);
  EXPECT_NEAR(f.at(5, "contact_density"), 0.5 / kBin5Volume, 1e-15);
}

// 3D: a wall transfer inside ring 2 whose middle lies on the y axis, where e_r = e_y and
// e_theta = -e_x. r = (0.6, 0, 0.8) = n, J = (0.2, 0.5, 1): in the local frame r = (0, -0.6,
// 0.8), J = (0.5, -0.2, 1), J.n = 0.92. Every part is rotated as stress_contact is.
TEST(FieldAccumulator, RingWallNormalAndFabricInTheLocalFrame) {
  FieldAccumulator<3> acc(jet3d_spec());
  Particles<3> p;
  p.add(0, GrainKind::kFree, {0.0, 0.0, 30.0}, Vec<3>::Zero(), 0.5, 1.0);
  p.add(1, GrainKind::kWall, {0.0, 0.0, 0.0}, Vec<3>::Zero(), 0.5, 1.0);
  acc.sample(p, {}, 0.0);
  const std::vector<PairImpulse<3>> transfer{
      {0, 1, {0.3, 5.0, 2.4}, {-0.3, 5.0, 1.6}, {0.2, 0.5, 1.0}}};
  acc.sample(p, transfer, 2.0);
  const Table f = acc.fields({});
  const double scale = 1.0 / (acc.layout().at(2, "volume") * 2.0);
  const Eigen::Vector3d r_local(0.0, -0.6, 0.8), j_local(0.5, -0.2, 1.0);
  expect_tensor(f, 2, "stress_contact", Eigen::Matrix3d(j_local * r_local.transpose() * scale),
                1e-15);
  expect_same_tensor(f, 2, "stress_contact_wall", "stress_contact", "rtz");
  expect_tensor(f, 2, "stress_contact_normal",
                Eigen::Matrix3d(0.92 * r_local * r_local.transpose() * scale), 1e-15);
  expect_tensor(f, 2, "fabric", Eigen::Matrix3d(r_local * r_local.transpose()), 1e-15);
  EXPECT_NEAR(f.at(2, "stress_contact.rz"), 0.4 * scale, 1e-15);
  EXPECT_NEAR(f.at(2, "stress_contact_normal.rz"), 0.0, 1e-15);  // n has no radial part here
}

// Central forces (the lattice's J = f r) have no tangential part, in every bin and both frames'
// geometry; the fabric of any bin with transfers has trace 1; no grain is a wall grain.
TYPED_TEST(FieldAccumulatorTyped, CentralForcesAreAllNormalAndFabricHasUnitTrace) {
  constexpr int D = TypeParam::value;
  const auto& axes = FieldAccumulator<D>::Coordinates::kAxes;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> acc(spec);
  acc.sample(Particles<D>{}, {}, 0.0);
  acc.sample(Particles<D>{}, lattice_bonds<D>(spec), 0.25);
  const Table f = acc.fields({});
  for (std::size_t bin = 0; bin < f.rows(); ++bin) {
    SCOPED_TRACE(bin);
    ASSERT_GT(f.at(bin, "contact_density"), 0.0);
    double trace = 0.0;
    for (int a = 0; a < D; ++a) {
      const std::string aa = std::string(axes[a]) + std::string(axes[a]);
      trace += f.at(bin, "fabric." + aa);
      for (int b = 0; b < D; ++b) {
        const std::string ab = std::string(axes[a]) + std::string(axes[b]);
        const double total = f.at(bin, "stress_contact." + ab);
        EXPECT_NEAR(f.at(bin, "stress_contact_normal." + ab), total,
                    1e-12 * std::abs(f.at(bin, "P")));
        EXPECT_EQ(f.at(bin, "stress_contact_wall." + ab), 0.0);
      }
    }
    EXPECT_NEAR(trace, 1.0, 1e-14);
  }
}

// Every field of `a` has the bits of `b`'s (a NaN matches a NaN), and most are finite.
void expect_same_fields(const Table& a, const Table& b) {
  ASSERT_EQ(a.names(), b.names());
  int finite = 0;
  for (const std::string& name : a.names())
    for (std::size_t bin = 0; bin < a.rows(); ++bin) {
      const double x = a.at(bin, name), y = b.at(bin, name);
      finite += std::isfinite(x);
      EXPECT_TRUE(std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y) ||
                  (std::isnan(x) && std::isnan(y)))
          << name << " in bin " << bin << ": " << x << " against " << y;
    }
  EXPECT_GT(finite, static_cast<int>(a.rows() * a.names().size() * 3 / 4));
}

// What reach() leaves out counts for nothing: a run over MPI ranks gathers to rank 0 only the
// grains and transfers that it holds (core/sample_region.hpp), and its fields must be those of
// all, bit for bit. Grains and short transfers scattered over a box well beyond the cylinder;
// the strain rates read the half-cells that overhang the bins, phi every grain that overlaps.
TYPED_TEST(FieldAccumulatorTyped, WhatItsReachLeavesOutCountsNothing) {
  constexpr int D = TypeParam::value;
  constexpr int kAxis = kJetAxis<D>;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> all(spec), held(spec);
  const SampleRegion region = all.reach();
  ASSERT_GT(region.within, spec.target_radius);
  std::mt19937_64 rng(83);
  std::uniform_real_distribution<double> across(-region.within - 2.0, region.within + 2.0);
  std::uniform_real_distribution<double> along(region.low - 4.0, region.high + 4.0);
  std::uniform_real_distribution<double> radius(0.4, 0.5), length(0.0, 1.1);
  std::normal_distribution<double> gauss;
  const auto point = [&] {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = d == kAxis ? along(rng) : across(rng);
    return x;
  };
  Particles<D> p, p_held;
  for (int i = 0; i < 6000; ++i) {
    const Vec<D> x = point();
    Vec<D> v;
    for (int d = 0; d < D; ++d) v[d] = gauss(rng) + (d == 0 ? 0.1 * x[D - 1] : 0.0);  // a shear
    const GrainKind kind = i % 50 == 0 ? GrainKind::kWall : GrainKind::kFree;
    const double r = radius(rng);
    p.add(i, kind, x, v, r, 1.0);
    if (region.holds_grain<D>(x, r, kind)) p_held.add(i, kind, x, v, r, 1.0);
  }
  std::vector<PairImpulse<D>> transfers, transfers_held;
  for (int k = 0; k < 6000; ++k) {
    const Vec<D> a = point();
    Vec<D> u;
    for (int d = 0; d < D; ++d) u[d] = gauss(rng);
    const Vec<D> b = a + length(rng) * u.normalized();
    Vec<D> impulse;
    for (int d = 0; d < D; ++d) impulse[d] = gauss(rng);
    const PairImpulse<D> t{GrainId(k % 6000), GrainId((7 * k + 1) % 6000), a, b, impulse};
    transfers.push_back(t);
    if (region.holds_transfer<D>(a, b)) transfers_held.push_back(t);
  }
  ASSERT_LT(p_held.size(), p.size() * 3 / 4) << "the box should reach well beyond the cylinder";
  ASSERT_LT(transfers_held.size(), transfers.size() * 3 / 4);
  all.sample(p, {}, 0.0);
  held.sample(p_held, {}, 0.0);
  all.sample(p, transfers, 0.3);
  held.sample(p_held, transfers_held, 0.3);
  expect_same_fields(all.fields({}), held.fields({}));
}

// Random grains and transfers in and around the mesh (a shear flow, some target grains).
template <int D>
std::pair<Particles<D>, std::vector<PairImpulse<D>>> random_sample(const BinSpec& spec,
                                                                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> length(0.2, 1.1);
  Particles<D> p;
  std::vector<PairImpulse<D>> transfers;
  for (int i = 0; i < 4000; ++i) {
    const Vec<D> x = random_point<D>(rng, spec, -1.0);
    Vec<D> v, u, impulse;
    for (int d = 0; d < D; ++d) {
      v[d] = 0.2 * gauss(rng) + (d == 0 ? 0.1 * x[D - 1] : 0.0);
      u[d] = gauss(rng);
      impulse[d] = gauss(rng);
    }
    p.add(i, i % 40 == 0 ? GrainKind::kWall : GrainKind::kFree, x, v, 0.5, 1.0);
    transfers.push_back(
        {GrainId(i), GrainId((7 * i + 1) % 4000), x, x + length(rng) * u.normalized(), impulse});
  }
  return {std::move(p), std::move(transfers)};
}

// The same grains and transfers in another order: every sum is exact, so every field, the
// velocity distributions' flatness among them, keeps its bits. (A run over MPI ranks sums its
// ranks' grains apart and in other orders.)
TYPED_TEST(FieldAccumulatorTyped, OrderOfGrainsAndTransfersChangesNoBit) {
  constexpr int D = TypeParam::value;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> in_order(spec), shuffled(spec);
  std::mt19937_64 rng(5);
  for (int s = 0; s < 3; ++s) {
    auto [p, transfers] = random_sample<D>(spec, 100 + s);
    in_order.sample(p, transfers, s == 0 ? 0.0 : 0.5);
    std::vector<std::uint32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    p.gather(order);
    std::shuffle(transfers.begin(), transfers.end(), rng);
    shuffled.sample(p, transfers, s == 0 ? 0.0 : 0.5);
  }
  expect_same_fields(in_order.fields({}), shuffled.fields({}));
  for (int c = 0; c < D; ++c) {
    const double x = in_order.velocity_distribution().flatness_region(c);
    EXPECT_TRUE(std::isfinite(x));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(x),
              std::bit_cast<std::uint64_t>(shuffled.velocity_distribution().flatness_region(c)));
  }
}

// A checkpoint of a granjet that kept plain sums (each sum rounded, under its own name) resumes:
// the rounded sums become the first terms, and the fields read as they did when it was written.
TYPED_TEST(FieldAccumulatorTyped, CheckpointOfPlainSumsResumes) {
  constexpr int D = TypeParam::value;
  const BinSpec spec = spec_for(D);
  FieldAccumulator<D> straight(spec);
  auto [p, transfers] = random_sample<D>(spec, 7);
  straight.sample(p, {}, 0.0);
  straight.sample(p, transfers, 0.5);
  StateArchive exact;
  StateWriter writer(exact, "f");
  straight.visit_state(writer);
  StateArchive plain;  // the older layout: name -> the rounded sum's components
  for (const auto& [name, values] : exact.all_reals()) plain.put_reals(name, values);
  int sums = 0;
  for (const auto& [name, words] : exact.all_integers()) {
    if (!name.ends_with("_exact")) {
      plain.put_integers(name, words);
      continue;
    }
    const std::size_t each = ExactSum{}.words().size(), components = words.size() / each;
    std::vector<double> rounded;
    for (std::size_t k = 0; k < components; ++k)
      rounded.push_back(ExactSum::of_words(std::span(words).subspan(k * each, each)).value());
    plain.put_reals(name.substr(0, name.size() - 6), rounded);
    ++sums;
  }
  ASSERT_GT(sums, 0);

  FieldAccumulator<D> from_exact(spec), from_plain(spec);
  StateReader exact_reader(exact, "f"), plain_reader(plain, "f");
  from_exact.visit_state(exact_reader);
  from_plain.visit_state(plain_reader);
  const Table expected = straight.fields({});
  expect_same_fields(from_exact.fields({}), expected);
  expect_same_fields(from_plain.fields({}), expected);
  // Both go on sampling.
  from_plain.sample(p, transfers, 0.5);
  from_exact.sample(p, transfers, 0.5);
  const Table c = from_exact.fields({}), d = from_plain.fields({});
  EXPECT_NEAR(c.at(0, "n"), d.at(0, "n"), 1e-12 * std::abs(c.at(0, "n")));
}

}  // namespace
}  // namespace granjet::analysis
