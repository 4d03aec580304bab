// The jet and target built from the shipped scene parameters [model §4-§5].
#include "core/initial_state.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

namespace granjet {
namespace {

template <int D>
std::int64_t count(const Particles<D>& p, GrainKind kind) {
  return std::count(p.kind().begin(), p.kind().end(), kind);
}

// Min over pairs of dist / (R_i + R_j); of the jet's grains only, or of all.
template <int D>
double min_distance_ratio(const Particles<D>& p, bool jet_only = false) {
  double worst = 1e9;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      if (jet_only && (p.kind()[i] != GrainKind::kFree || p.kind()[j] != GrainKind::kFree))
        continue;
      worst = std::min(
          worst, (p.position()[i] - p.position()[j]).norm() / (p.radius()[i] + p.radius()[j]));
    }
  return worst;
}

TEST(InitialState, Jet3dHas20000GrainsInTheCylinderAnd439TargetGrains) {
  Scene s;  // defaults are jet3d's
  const Particles<3> p = build_initial_state<3>(s);
  EXPECT_EQ(count(p, GrainKind::kFree), 20000);
  EXPECT_EQ(count(p, GrainKind::kWall), 439);  // as the LAMMPS peer's target (D_tar = 22)
  double z_min = 1e9;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec<3>& x = p.position()[i];
    if (p.kind()[i] == GrainKind::kWall) {
      EXPECT_EQ(x.z(), 0.0);
      EXPECT_LE(x.head<2>().norm(), 11.0 + 1e-9);
      continue;
    }
    EXPECT_LE(x.head<2>().norm(), 5.0 * (1.0 + 1e-9) + 1e-9);  // the lattice's clearance
    EXPECT_EQ(p.velocity()[i], Vec<3>(0, 0, -1));
    z_min = std::min(z_min, x.z());
  }
  EXPECT_NEAR(z_min, 2.0, 1e-12);  // a surface gap of 1 d to the target
}

// jet3d's fcc neighbours touch (spacing 1 d) without overlapping: in floating point a third of
// them would overlap by ~1e-16 d and start as contacts of no force, so the lattice is spread by
// a relative 1e-9.
TEST(InitialState, Jet3dTouchingNeighboursStartApartByTheClearance) {
  Scene s;
  s.jet.grains = 2000;
  const double ratio = min_distance_ratio(build_initial_state<3>(s), true);
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(ratio, 1.0 + 2e-9);
}

// The plate takes the target grains' place: the same jet, no target grains.
TEST(InitialState, PlateSceneHasTheJetAndNoTargetGrains) {
  Scene s;
  s.wall.kind = WallKind::kPlate;
  const Particles<3> p = build_initial_state<3>(s);
  EXPECT_EQ(count(p, GrainKind::kFree), 20000);
  EXPECT_EQ(count(p, GrainKind::kWall), 0);
  s.wall.kind = WallKind::kFixed;
  const Particles<3> grains = build_initial_state<3>(s);
  for (std::size_t i = 0; i < p.size(); ++i) EXPECT_EQ(p.position()[i], grains.position()[i]);
}

TEST(InitialState, KeptFractionIsPhiTilde) {
  Scene s;
  s.jet.grains = 4000;
  s.jet.phi_tilde = 0.6;
  const Particles<3> p = build_initial_state<3>(s);
  // Count the full lattice sites below the top of the jet to get the kept fraction.
  Scene full = s;
  full.jet.phi_tilde = 1.0;
  full.jet.grains = 20000;
  const Particles<3> all = build_initial_state<3>(full);
  double top = 0;
  for (std::size_t i = 0; i < p.size(); ++i) top = std::max(top, p.position()[i].z());
  std::int64_t sites = 0;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (all.kind()[i] == GrainKind::kFree && all.position()[i].z() <= top) ++sites;
  EXPECT_NEAR(4000.0 / sites, 0.6, 0.02);
}

// The extent of the jet column along its axis, front to back grain centre.
template <int D>
double column_length(const Particles<D>& p) {
  double lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] == GrainKind::kFree) {
      lo = std::min(lo, p.position()[i][D == 3 ? 2 : 0]);
      hi = std::max(hi, p.position()[i][D == 3 ? 2 : 0]);
    }
  return hi - lo;
}

// What budgets and plans know before building: the built state agrees.
TEST(InitialState, SizesBeforeBuildingMatchTheBuiltState) {
  Scene s;  // jet3d
  Particles<3> p3 = build_initial_state<3>(s);
  EXPECT_EQ(target_grains_estimate(s), static_cast<double>(count(p3, GrainKind::kWall)));
  EXPECT_NEAR(jet_column_length(s) / column_length(p3), 1.0, 0.03);
  s.wall.lattice = WallLattice::kSquare;
  s.wall.spacing = 1.2;
  p3 = build_initial_state<3>(s);
  EXPECT_NEAR(target_grains_estimate(s) / static_cast<double>(count(p3, GrainKind::kWall)), 1.0,
              0.03);
  s.jet.shape = JetShape::kRectangle;
  s.jet.aspect_ratio = 4.0;
  s.jet.area = 16.0;
  s.jet.grains = 4000;
  // A cross section 2 d across holds fewer lattice sites than its area over a site's: the
  // estimate, which counts by area, is a few percent long.
  EXPECT_NEAR(jet_column_length(s) / column_length(build_initial_state<3>(s)), 1.0, 0.05);

  Scene flat;  // jet2d
  flat.dimension = 2;
  flat.jet.diameter = 30;
  flat.jet.grains = 8000;
  flat.jet.spacing = 1.1;
  flat.wall.diameter = 66;
  const Particles<2> p2 = build_initial_state<2>(flat);
  EXPECT_EQ(target_grains_estimate(flat), static_cast<double>(count(p2, GrainKind::kWall)));
  EXPECT_NEAR(jet_column_length(flat) / column_length(p2), 1.0, 0.03);

  // The gas box holds gas.grains at exactly gas.phi: the lattice's box has the estimate's volume.
  Scene gas;
  gas.kind = SceneKind::kGas;
  gas.gas.grains = 4000;
  gas.gas.phi = 0.3;
  const Vec<3> box = gas_lattice<3>(gas.gas).box;
  EXPECT_NEAR(box.prod(), std::pow(gas_box_edge(gas), 3), 1e-9 * box.prod());
  gas.dimension = 2;
  const Vec<2> area = gas_lattice<2>(gas.gas).box;
  EXPECT_NEAR(area.prod(), std::pow(gas_box_edge(gas), 2), 1e-9 * area.prod());
}

TEST(InitialState, Jet2dBidisperseHalfSmallNoOverlap67TargetDisks) {
  Scene s;
  s.dimension = 2;
  s.jet.diameter = 30;
  s.jet.grains = 2000;
  s.jet.spacing = 1.1;
  s.jet.dispersity = Dispersity::kBi;
  s.wall.diameter = 66;
  const Particles<2> p = build_initial_state<2>(s);
  EXPECT_EQ(count(p, GrainKind::kWall), 67);
  std::int64_t small = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind()[i] == GrainKind::kWall) continue;
    small += p.radius()[i] == 0.4;
    EXPECT_LE(std::abs(p.position()[i].y()), 15.0 + 1e-9);
    EXPECT_EQ(p.velocity()[i], Vec<2>(-1, 0));
  }
  EXPECT_EQ(small, 1000);
  EXPECT_GE(min_distance_ratio(p), 1.0 - 1e-12);
}

// Spec §5 anisotropy runs: jet3d's fcc lattice, every site kept, cut to a rectangle of area A and
// aspect ratio l (long side sqrt(A l) along x, short side sqrt(A/l) along y); plate target.
Scene rectangle_jet(double area, double l, std::int64_t grains) {
  Scene s;
  s.jet.shape = JetShape::kRectangle;
  s.jet.area = area;
  s.jet.aspect_ratio = l;
  s.jet.phi_tilde = 1.0;
  s.jet.grains = grains;
  s.wall.kind = WallKind::kPlate;
  return s;
}

// The (x, y) of the jet grains per lattice layer, keyed by the layer's height in 1e-6 d.
std::map<long, std::vector<std::pair<double, double>>> layers_of(const Particles<3>& p) {
  std::map<long, std::vector<std::pair<double, double>>> layers;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] == GrainKind::kFree) {
      const Vec<3>& x = p.position()[i];
      layers[std::lround(x.z() * 1e6)].emplace_back(x.x(), x.y());
    }
  return layers;
}

// Every site inside the rectangle (up to the lattice's relative clearance 1e-9), and the lattice
// reaching each side to within the row spacing a/2 = 0.707 d (so the cut is not smaller).
TEST(InitialState, RectangularJetSitesLieInTheRectangle) {
  for (double l : {1.0, 2.0, 4.0}) {
    SCOPED_TRACE(l);
    const Scene s = rectangle_jet(16.0, l, 400);
    const double half_long = 0.5 * std::sqrt(16.0 * l), half_short = 0.5 * std::sqrt(16.0 / l);
    double x_max = 0.0, y_max = 0.0;
    for (const auto& [z, sites] : layers_of(build_initial_state<3>(s)))
      for (const auto& [x, y] : sites) {
        EXPECT_LE(std::abs(x), half_long + 1e-6);
        EXPECT_LE(std::abs(y), half_short + 1e-6);
        x_max = std::max(x_max, std::abs(x));
        y_max = std::max(y_max, std::abs(y));
      }
    EXPECT_GT(x_max, half_long - 0.5 * std::sqrt(2.0));
    EXPECT_GT(y_max, half_short - 0.5 * std::sqrt(2.0));
    if (l > 1.0) {
      EXPECT_GT(x_max, y_max);  // the long side along x
    }
  }
}

// l = 1 is the square of side sqrt(A): each layer's sites are the same set after swapping x
// and y (an fcc (100) layer is symmetric under the swap).
TEST(InitialState, RectangularJetOfAspectRatioOneIsASquare) {
  const Scene s = rectangle_jet(16.0, 1.0, 400);
  for (auto [z, sites] : layers_of(build_initial_state<3>(s))) {
    std::vector<std::pair<double, double>> swapped;
    for (const auto& [x, y] : sites) swapped.emplace_back(y, x);
    const auto key = [](const std::pair<double, double>& p) {
      return std::pair(std::lround(p.first * 1e6), std::lround(p.second * 1e6));
    };
    std::vector<std::pair<long, long>> a, b;
    for (const auto& p : sites) a.push_back(key(p));
    for (const auto& p : swapped) b.push_back(key(p));
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "layer at z = " << z * 1e-6;
  }
}

// Each fcc (100) layer (cube edge a = sqrt 2 d) is a centred rectangular lattice: rows every a/2
// along y, sites every a along each row, 2/a^2 = 1 site per d^2. A rectangle L x W holds
// between L/a - 1 and L/a + 1 sites per row and between 2W/a - 1 and 2W/a + 1 rows, so a full
// layer's count differs from A 2/a^2 by at most (L + 2W)/a + 1: 9.5 for the study's A = 16,
// 86 (5%) for A = 1600. Every complete layer is checked (the last one is cut by jet.grains).
TEST(InitialState, RectangularJetLayersHoldAreaTimesLatticeDensity) {
  const double a = std::sqrt(2.0);
  for (double area : {16.0, 1600.0})
    for (double l : {1.0, 4.0}) {
      SCOPED_TRACE(::testing::Message() << "A = " << area << ", l = " << l);
      const Scene s = rectangle_jet(area, l, static_cast<std::int64_t>(6.5 * area));
      const double long_side = std::sqrt(area * l), short_side = std::sqrt(area / l);
      const double bound = (long_side + 2.0 * short_side) / a + 1.0;
      const auto layers = layers_of(build_initial_state<3>(s));
      ASSERT_GE(layers.size(), 5u);
      int checked = 0;
      for (auto it = layers.begin(); std::next(it) != layers.end(); ++it, ++checked)
        EXPECT_NEAR(static_cast<double>(it->second.size()), area * 2.0 / (a * a), bound);
      EXPECT_GE(checked, 4);
    }
}

// Wall lattices (model §4 leaves the layer's arrangement open): the target grains' positions.
template <int D>
std::vector<Vec<D>> wall_positions(const Particles<D>& p) {
  std::vector<Vec<D>> x;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] == GrainKind::kWall) x.push_back(p.position()[i]);
  return x;
}

template <class V>
double min_pair_distance(const std::vector<V>& x) {
  double d = 1e9;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) d = std::min(d, (x[i] - x[j]).norm());
  return d;
}

TEST(InitialState, SquareWallLatticeHoldsTheIntegerPointsOfTheDisk) {
  Scene s;
  s.jet.grains = 100;
  s.wall.lattice = WallLattice::kSquare;
  s.wall.spacing = 1.25;
  const std::vector<Vec<3>> wall = wall_positions(build_initial_state<3>(s));
  // Sites (1.25 i, 1.25 j) with |.| <= 11, counted directly.
  int expected = 0;
  for (int i = -9; i <= 9; ++i)
    for (int j = -9; j <= 9; ++j) expected += 1.5625 * (i * i + j * j) <= 121.0 + 1e-9;
  EXPECT_EQ(static_cast<int>(wall.size()), expected);
  EXPECT_NEAR(min_pair_distance(wall), 1.25, 1e-12);
  for (const Vec<3>& x : wall) {
    EXPECT_NEAR(std::remainder(x.x(), 1.25), 0.0, 1e-12);
    EXPECT_NEAR(std::remainder(x.y(), 1.25), 0.0, 1e-12);
  }
}

// Spread (1.2 d) or overlapping (0.6 d: a smoother layer) target grains keep the lattice's spacing.
TEST(InitialState, HexagonalWallSpacingSetsTheNeighbourDistance) {
  for (const double spacing : {1.2, 0.6}) {
    Scene s;
    s.jet.grains = 100;
    s.wall.spacing = spacing;
    const std::vector<Vec<3>> wall = wall_positions(build_initial_state<3>(s));
    EXPECT_NEAR(min_pair_distance(wall), spacing, 1e-12);
    // Density of a hexagonal layer: 2/(sqrt 3 a^2) sites per unit area over the disk of radius 11.
    const double expected = std::numbers::pi * 121.0 * 2.0 / (std::sqrt(3.0) * spacing * spacing);
    EXPECT_NEAR(static_cast<double>(wall.size()), expected, 0.05 * expected) << spacing;
  }
}

// A random layer: sites shifted by at most the jitter, never overlapping, the same for the same
// seed, and the jet untouched (its own random stream).
TEST(InitialState, JitteredWallStaysNearItsSitesWithoutOverlapAndLeavesTheJetAlone) {
  Scene s;
  s.jet.grains = 300;
  s.wall.spacing = 1.3;
  const Particles<3> plain = build_initial_state<3>(s);
  s.wall.jitter = 0.15;
  const Particles<3> a = build_initial_state<3>(s), b = build_initial_state<3>(s);
  ASSERT_EQ(a.size(), plain.size());
  double largest = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec<3> shift = a.position()[i] - plain.position()[i];
    if (a.kind()[i] == GrainKind::kFree) {
      EXPECT_EQ(shift.norm(), 0.0);
      continue;
    }
    EXPECT_EQ(shift.z(), 0.0);
    largest = std::max(largest, shift.norm());
    moved += shift.norm() > 0.0;
  }
  EXPECT_LE(largest, 0.15);
  EXPECT_GT(largest, 0.12);  // the shifts fill the disk of radius 0.15
  EXPECT_EQ(moved, static_cast<double>(wall_positions(a).size()));
  EXPECT_GE(min_pair_distance(wall_positions(a)), 1.0);
  EXPECT_TRUE(std::equal(a.position().begin(), a.position().end(), b.position().begin()));
}

TEST(InitialState, Jitter2dShiftsTheRowAlongItself) {
  Scene s;
  s.dimension = 2;
  s.jet.grains = 200;
  s.jet.diameter = 30;
  s.wall.diameter = 66;
  s.wall.spacing = 1.2;
  s.wall.jitter = 0.1;
  const std::vector<Vec<2>> wall = wall_positions(build_initial_state<2>(s));
  EXPECT_EQ(wall.size(), 55u);  // y = 1.2 c for |c| <= 27
  for (const Vec<2>& x : wall) {
    EXPECT_EQ(x.x(), 0.0);
    EXPECT_LE(std::abs(std::remainder(x.y(), 1.2)), 0.1 + 1e-12);
  }
  EXPECT_GE(min_pair_distance(wall), 1.0);
}

TEST(InitialState, SameSeedSameJetOtherSeedOther) {
  Scene s;
  s.jet.grains = 500;
  const Particles<3> a = build_initial_state<3>(s), b = build_initial_state<3>(s);
  s.run.seed = 2;
  const Particles<3> c = build_initial_state<3>(s);
  EXPECT_TRUE(std::equal(a.position().begin(), a.position().end(), b.position().begin()));
  EXPECT_FALSE(std::equal(a.position().begin(), a.position().end(), c.position().begin()));
}

// The shares of `parts` ranks hold the whole state's jet grains once each, bit for bit, and the
// whole target each; a share's jet grains are a run of ids.
template <int D>
void expect_shares_make_the_whole(const Scene& s, int parts) {
  const Particles<D> whole = build_initial_state<D>(s);
  std::map<GrainId, int> held;
  for (int part = 0; part < parts; ++part) {
    const Particles<D> share = build_initial_state<D>(s, {part, parts});
    std::int64_t jet = 0;
    for (std::size_t k = 0; k < share.size(); ++k) {
      const GrainId id = share.id()[k];
      const auto i = static_cast<std::size_t>(id);  // the whole state's grains are in id order
      ASSERT_EQ(whole.id()[i], id);
      EXPECT_EQ(share.kind()[k], whole.kind()[i]);
      EXPECT_EQ(share.position()[k], whole.position()[i]) << "grain " << id;
      EXPECT_EQ(share.velocity()[k], whole.velocity()[i]);
      EXPECT_EQ(share.radius()[k], whole.radius()[i]);
      EXPECT_EQ(share.mass()[k], whole.mass()[i]);
      if (share.kind()[k] == GrainKind::kFree) {
        EXPECT_EQ(id, s.jet.grains * part / parts + jet++);
        ++held[id];
      }
    }
    EXPECT_EQ(jet, s.jet.grains * (part + 1) / parts - s.jet.grains * part / parts);
    EXPECT_EQ(count(share, GrainKind::kWall), count(whole, GrainKind::kWall));
  }
  EXPECT_EQ(static_cast<std::int64_t>(held.size()), count(whole, GrainKind::kFree));
  for (const auto& [id, times] : held) EXPECT_EQ(times, 1) << "grain " << id;
}

TEST(InitialState, SharesOverRanksMakeTheWholeJet) {
  Scene s;
  s.jet.grains = 1000;
  expect_shares_make_the_whole<3>(s, 3);
  s.jet.dispersity = Dispersity::kBi;
  expect_shares_make_the_whole<3>(s, 4);
  s.dimension = 2;
  s.jet.diameter = 30;
  s.jet.spacing = 1.1;
  s.wall.diameter = 66;
  expect_shares_make_the_whole<2>(s, 5);
  s.wall.kind = WallKind::kPlate;
  expect_shares_make_the_whole<2>(s, 2);
}

TEST(InitialState, SharesOfTheBinarySceneSplitItsTwoGrains) {
  Scene s;
  s.kind = SceneKind::kBinary;
  const Particles<3> whole = build_initial_state<3>(s);
  const Particles<3> first = build_initial_state<3>(s, {0, 2});
  const Particles<3> second = build_initial_state<3>(s, {1, 2});
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(first.id()[0], 0);
  EXPECT_EQ(second.id()[0], 1);
  EXPECT_EQ(first.position()[0], whole.position()[0]);
  EXPECT_EQ(second.velocity()[0], whole.velocity()[1]);
}

}  // namespace
}  // namespace granjet
