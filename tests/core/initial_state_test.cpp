// The jet and target built from the shipped scene parameters [spec §4-§5].
#include "core/initial_state.hpp"

#include <gtest/gtest.h>

#include <algorithm>

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
      worst = std::min(worst, (p.position()[i] - p.position()[j]).norm() /
                                  (p.radius()[i] + p.radius()[j]));
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

TEST(InitialState, SameSeedSameJetOtherSeedOther) {
  Scene s;
  s.jet.grains = 500;
  const Particles<3> a = build_initial_state<3>(s), b = build_initial_state<3>(s);
  s.run.seed = 2;
  const Particles<3> c = build_initial_state<3>(s);
  EXPECT_TRUE(std::equal(a.position().begin(), a.position().end(), b.position().begin()));
  EXPECT_FALSE(std::equal(a.position().begin(), a.position().end(), c.position().begin()));
}

}  // namespace
}  // namespace granjet
