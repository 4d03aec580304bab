// Conformance: total momentum is conserved to round-off on both backends (equal and opposite
// pair forces, or impulses) in an inelastic frictionless cluster with many collisions.
#include <gtest/gtest.h>

#include <cmath>

#include "backends.hpp"
#include "core/random.hpp"

namespace granjet {
namespace {

template <class T>
class MomentumConformance : public ::testing::Test {};
TYPED_TEST_SUITE(MomentumConformance, testing::AllBackends);

// Grains on a square (cubic) lattice of spacing 1.05 with random velocities of order 1 and
// masses between 1 and 2.
template <int D>
Particles<D> cluster(int per_side, std::uint64_t seed) {
  Random rng(seed);
  Particles<D> p;
  const int total = static_cast<int>(std::pow(per_side, D));
  for (int n = 0; n < total; ++n) {
    Vec<D> x, v;
    int rest = n;
    for (int d = 0; d < D; ++d) {
      x[d] = 1.05 * (rest % per_side);
      rest /= per_side;
      v[d] = 2.0 * rng.uniform() - 1.0;
    }
    p.add(n, GrainKind::kFree, x, v, 0.5, 1.0 + rng.uniform());
  }
  return p;
}

TYPED_TEST(MomentumConformance, ConservedToRoundOffThroughManyCollisions) {
  using Backend = typename TypeParam::Backend;
  constexpr int D = TypeParam::D;
  Scene scene;
  scene.kind = SceneKind::kBinary;  // free space
  scene.dimension = D;
  scene.contact.restitution = 0.75;
  scene.contact.friction = 0.0;
  scene.ed.restitution_law = RestitutionLaw::kConstant;
  const Particles<D> start = cluster<D>(D == 2 ? 12 : 6, 3);
  auto sim = Backend::template make<D>(scene, start);
  sim->advance_to(5.0);
  EXPECT_GT(sim->energy().dissipated, 0.05 * (sim->energy().kinetic + sim->energy().dissipated));
  EXPECT_NEAR((total_momentum(sim->particles()) - total_momentum(start)).norm(), 0.0,
              1e-13 * start.size());
}

}  // namespace
}  // namespace granjet
