// Conformance: the flat target plate (wall.kind = plate, core/plate_face.hpp) on both backends,
// the same test body. A grain hitting the face head-on comes back with e times its speed [2.1]
// against an infinite mass, losing (1 - e^2) m v^2 / 2, and the plate's impulses handed to the
// analysis add up to m (1 + e) v; a grain beside the edge flies on untouched.
#include <gtest/gtest.h>

#include "backends.hpp"
#include "core/jet_geometry.hpp"
#include "core/plate_face.hpp"

namespace granjet {
namespace {

template <class T>
class PlateConformance : public ::testing::Test {};
TYPED_TEST_SUITE(PlateConformance, testing::AllBackends);

TYPED_TEST(PlateConformance, Eq2_1_HeadOnOnThePlateGivesTheRestitution) {
  using Backend = typename TypeParam::Backend;
  constexpr int D = TypeParam::D;
  constexpr int kAxis = kJetAxis<D>;
  for (const double e : {0.5, 0.75, 0.9}) {
    SCOPED_TRACE(std::string(Backend::kName) + " e = " + std::to_string(e));
    Scene scene;
    scene.kind = SceneKind::kJet;
    scene.dimension = D;
    scene.wall.kind = WallKind::kPlate;
    scene.wall.diameter = 22.0;
    scene.contact.restitution = e;
    scene.contact.friction = 0.0;
    scene.ed.restitution_law = RestitutionLaw::kConstant;
    Particles<D> grains;
    Vec<D> x = Vec<D>::Zero(), v = Vec<D>::Zero();
    // binary.ini's gap: a contact that starts exactly on a step (a gap of 25 steps, 0.05) gives
    // AB2 e = 0.513 for 0.5 against a pair of grains as against the plate.
    x[kAxis] = kTargetSurface + 0.5 + 0.0537;
    v[kAxis] = -1.0;
    grains.add(1, GrainKind::kFree, x, v, 0.5, 1.0);
    x[1 - kAxis % 2] = 12.0;  // beside the edge (radius 11), its centre never over the face
    grains.add(2, GrainKind::kFree, x, v, 0.5, 1.0);
    auto sim = Backend::template make<D>(scene, grains);
    sim->record_transfers(true);
    sim->advance_to(0.5);  // contact from t = 0.054 to 0.154 (soft) or at 0.054 (hard)
    const Particles<D>& after = sim->particles();
    const std::size_t hit = after.id()[0] == 1 ? 0 : 1, beside = 1 - hit;
    EXPECT_NEAR(after.velocity()[hit][kAxis] / e, 1.0, Backend::kRestitutionTolerance);
    EXPECT_NEAR(after.velocity()[hit].norm() / e, 1.0, Backend::kRestitutionTolerance);
    EXPECT_EQ(after.velocity()[beside], v);
    const double loss = 0.5 * (1.0 - e * e);
    EXPECT_NEAR(sim->energy().dissipated / loss, 1.0,
                std::max(2.0 * e * e / (1.0 - e * e) * Backend::kRestitutionTolerance, 1e-14));
    std::vector<PairImpulse<D>> transfers;
    sim->collect_transfers(transfers);
    Vec<D> on_grain = Vec<D>::Zero();
    for (const PairImpulse<D>& t : transfers)
      if (t.j == kPlateId) on_grain += t.impulse;
    if (std::string(Backend::kName) == "event_driven") {  // the soft backend samples forces
      EXPECT_NEAR(on_grain[kAxis], 1.0 + e, 1e-14);
    }
  }
}

}  // namespace
}  // namespace granjet
