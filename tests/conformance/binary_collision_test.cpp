// Conformance [model §1]: the binary head-on collision on both backends, the same test body.
// Measured from the trajectory (velocities long before and long after contact, along the line
// of centres): restitution e, and the energy loss (1 - e^2)/4 m (k.v12)^2 of [2.1]. The soft
// backend's 0.5% on e propagates to 2 e^2/(1 - e^2) times that on the loss.
#include <gtest/gtest.h>

#include "backends.hpp"
#include "run/backend_factory.hpp"

namespace granjet {
namespace {

template <class T>
class BinaryConformance : public ::testing::Test {};
TYPED_TEST_SUITE(BinaryConformance, testing::AllBackends);

TYPED_TEST(BinaryConformance, Eq2_1_HeadOnGivesTheRestitutionAndItsEnergyLoss) {
  using Backend = typename TypeParam::Backend;
  constexpr int D = TypeParam::D;
  for (const double e : {0.5, 0.75, 0.9}) {
    SCOPED_TRACE(std::string(Backend::kName) + " e = " + std::to_string(e));
    Scene scene;
    scene.kind = SceneKind::kBinary;
    scene.dimension = D;
    scene.contact.restitution = e;
    scene.contact.friction = 0.0;
    scene.ed.restitution_law = RestitutionLaw::kConstant;
    auto sim = make_simulator<D>(Backend::kName, scene);
    const Particles<D> before = sim->particles();
    sim->advance_to(0.5);  // contact from t = 0.054 to 0.154 (soft) or at 0.054 (hard)
    const Particles<D> after = sim->particles();
    const auto v12 = [](const Particles<D>& p) { return (p.velocity()[0] - p.velocity()[1])[0]; };
    const double measured = -v12(after) / v12(before);
    EXPECT_NEAR(measured / e, 1.0, Backend::kRestitutionTolerance);
    const double loss = 0.25 * (1.0 - e * e) * v12(before) * v12(before);
    const double loss_tolerance =
        std::max(2.0 * e * e / (1.0 - e * e) * Backend::kRestitutionTolerance, 1e-14);
    EXPECT_NEAR(sim->energy().dissipated / loss, 1.0, loss_tolerance);
  }
}

}  // namespace
}  // namespace granjet
