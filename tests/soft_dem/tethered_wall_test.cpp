// The tethered target [model §4]: anchors and neighbour springs k_w with dashpots eta_w, over the
// wall lattices the scene keys offer.
#include "soft_dem/tethered_wall.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "core/initial_state.hpp"
#include "core/scene.hpp"

namespace granjet::dem {
namespace {

template <int D>
TetheredWall<D> wall_of(const Scene& s, const Particles<D>& p) {
  return TetheredWall<D>(p, s.wall.spring, 0.0,
                         (s.wall.spacing + 2.0 * s.wall.jitter) * (1 + 1e-6));
}

// The springs' elastic energy, every term of it.
double elastic_energy(const TetheredWall<3>& wall, const Particles<3>& p) {
  double e = 0.0;
  wall.for_each_energy_term(p, [&](std::size_t, std::size_t, double term) { e += term; });
  return e;
}

// Bonds join lattice neighbours only: pairs of sites (i, j), (i+1, j) or (i, j+1) of a square
// lattice of spacing a both inside the disk of radius 11, counted from the lattice indices; the
// jitter moves the grains but must not change who is bonded.
TEST(TetheredWall, Sec4_BondsJoinSquareLatticeNeighboursEvenWhenJittered) {
  Scene s;
  s.jet.grains = 10;
  s.wall.lattice = WallLattice::kSquare;
  s.wall.spacing = 1.3;
  s.wall.jitter = 0.1;
  const auto inside = [](int i, int j) { return 1.69 * (i * i + j * j) <= 121.0 + 1e-9; };
  std::size_t expected = 0;
  for (int i = -10; i <= 10; ++i)
    for (int j = -10; j <= 10; ++j)
      if (inside(i, j)) expected += inside(i + 1, j) + inside(i, j + 1);
  EXPECT_EQ(wall_of(s, build_initial_state<3>(s)).bonds(), expected);
}

// The hexagonal layer's interior grains have six neighbours; a 2D row of n grains has n - 1
// bonds.
TEST(TetheredWall, Sec4_HexagonalLayerAndRowBondCounts) {
  Scene s3;
  s3.jet.grains = 10;
  s3.wall.spacing = 1.1;
  const TetheredWall<3> layer = wall_of(s3, build_initial_state<3>(s3));
  std::size_t sites = 0;
  const Particles<3> p3 = build_initial_state<3>(s3);
  for (std::size_t i = 0; i < p3.size(); ++i) sites += p3.kind()[i] == GrainKind::kWall;
  // Between 3 per site (the boundary's share) and the interior's 3.
  EXPECT_LT(layer.bonds(), 3 * sites);
  EXPECT_GT(layer.bonds(), 3 * sites * 9 / 10);

  Scene s2;
  s2.dimension = 2;
  s2.jet.grains = 10;
  s2.jet.diameter = 30;
  s2.wall.diameter = 66;
  s2.wall.spacing = 1.4;
  EXPECT_EQ(wall_of(s2, build_initial_state<2>(s2)).bonds(), 46u);  // 47 grains at 1.4 c, |c| <= 23
}

// The spring forces are minus the gradient of the elastic energy (no dashpot at rest).
TEST(TetheredWall, Sec4_SpringForceIsMinusTheEnergyGradient) {
  Scene s;
  s.jet.grains = 10;
  s.jet.diameter = 4;
  s.wall.diameter = 6;
  s.wall.lattice = WallLattice::kSquare;
  s.wall.spacing = 1.2;
  Particles<3> p = build_initial_state<3>(s);
  const TetheredWall<3> wall = wall_of(s, p);
  std::vector<std::size_t> walls;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] == GrainKind::kWall) walls.push_back(i);
  // Strain the layer by moving every wall grain a little, differently.
  for (std::size_t k = 0; k < walls.size(); ++k)
    p.position()[walls[k]] += Vec<3>(0.01 * (k % 3), -0.02 * (k % 2), 0.015 * (k % 5));
  std::vector<Vec<3>> force(p.size(), Vec<3>::Zero());
  wall.add_forces(p, force);
  const std::size_t probe = walls[walls.size() / 2];
  const double h = 1e-6;
  for (int a = 0; a < 3; ++a) {
    Particles<3> plus = p, minus = p;
    plus.position()[probe][a] += h;
    minus.position()[probe][a] -= h;
    const double gradient = (elastic_energy(wall, plus) - elastic_energy(wall, minus)) / (2 * h);
    EXPECT_NEAR(force[probe][a], -gradient, 1e-6) << "axis " << a;
  }
}

// The springs find their grains again after the grains are reordered (a neighbour rebuild
// sorts them by cell): each grain gets the same force, bit for bit, where it now lies.
TEST(TetheredWall, Sec4_SpringsFollowTheirGrainsWhenTheGrainsAreReordered) {
  Scene s;
  s.jet.grains = 10;
  s.jet.diameter = 4;
  s.wall.diameter = 6;
  s.wall.spacing = 1.2;
  Particles<3> p = build_initial_state<3>(s);
  TetheredWall<3> wall = wall_of(s, p);
  for (std::size_t i = 0; i < p.size(); ++i)
    p.position()[i] += Vec<3>(0.01 * (i % 3), -0.02 * (i % 2), 0.015 * (i % 5));
  std::vector<Vec<3>> before(p.size(), Vec<3>::Zero());
  wall.add_forces(p, before);
  std::vector<std::uint32_t> reversed(p.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    reversed[k] = static_cast<std::uint32_t>(p.size() - 1 - k);
  Particles<3> q = p;
  q.gather(reversed, 1);
  wall.locate([&](GrainId id) { return static_cast<std::size_t>(p.size() - 1 - id); }, q.size());
  std::vector<Vec<3>> after(q.size(), Vec<3>::Zero());
  wall.add_forces(q, after);
  std::size_t pushed = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(q.id()[p.size() - 1 - i], p.id()[i]);
    EXPECT_EQ(after[p.size() - 1 - i], before[i]) << "grain " << p.id()[i];
    pushed += before[i] != Vec<3>::Zero();
  }
  EXPECT_GT(pushed, 10u);
}

}  // namespace
}  // namespace granjet::dem
