// Conformance: total momentum is conserved to round-off on both backends (equal and opposite
// pair forces, or impulses) in an inelastic frictionless cluster with many collisions.
#include <gtest/gtest.h>

#include <cmath>

#include "../common/lattice_cluster.hpp"
#include "backends.hpp"

namespace granjet {
namespace {

template <class T>
class MomentumConformance : public ::testing::Test {};
TYPED_TEST_SUITE(MomentumConformance, testing::AllBackends);

TYPED_TEST(MomentumConformance, ConservedToRoundOffThroughManyCollisions) {
  using Backend = typename TypeParam::Backend;
  constexpr int D = TypeParam::D;
  Scene scene;
  scene.kind = SceneKind::kBinary;  // free space
  scene.dimension = D;
  scene.contact.restitution = 0.75;
  scene.contact.friction = 0.0;
  scene.ed.restitution_law = RestitutionLaw::kConstant;
  const Particles<D> start = testing::lattice_cluster<D>(D == 2 ? 12 : 6, 3, 1.0, 1.0);
  auto sim = Backend::template make<D>(scene, start);
  sim->advance_to(5.0);
  EXPECT_GT(sim->energy().dissipated, 0.05 * (sim->energy().kinetic + sim->energy().dissipated));
  EXPECT_NEAR((total_momentum(sim->particles()) - total_momentum(start)).norm(), 0.0,
              1e-13 * start.size());
}

}  // namespace
}  // namespace granjet
