// The scene keys and scenes of the event-driven backend and the periodic gases: the shipped
// scenes load, the resolved INI reproduces them, and the starting gas state is what the keys say.
#include <gtest/gtest.h>

#include <sstream>

#include "core/initial_state.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

const std::string kScenes = GRANJET_SCENES_DIR;

TEST(EventDrivenScenes, ShippedGasScenesLoadAndRoundTrip) {
  const Scene gas3d = load_scene(kScenes + "/gas3d.ini", {});
  EXPECT_EQ(gas3d.kind, SceneKind::kGas);
  EXPECT_EQ(gas3d.gas.grains, 10976);
  EXPECT_DOUBLE_EQ(gas3d.contact.restitution, 1.0);
  const Scene hcs2d = load_scene(kScenes + "/hcs2d.ini", {});
  EXPECT_EQ(hcs2d.kind, SceneKind::kHcs);
  EXPECT_EQ(hcs2d.dimension, 2);
  EXPECT_EQ(hcs2d.ed.restitution_law, RestitutionLaw::kConstant);
  EXPECT_EQ(load_scene(kScenes + "/hcs3d.ini", {}).kind, SceneKind::kHcs);
  EXPECT_EQ(load_scene(kScenes + "/gas2d.ini", {}).dimension, 2);
  // The jets default to the velocity-dependent law.
  EXPECT_EQ(load_scene(kScenes + "/jet2d.ini", {}).ed.restitution_law,
            RestitutionLaw::kVelocityDependent);
  const Scene s = load_scene(kScenes + "/gas3d.ini",
                             {"ed.restitution_law=tc_model", "ed.tc=0.05", "gas.phi=0.45"});
  const std::string ini = scene_to_ini(s);
  std::istringstream in(ini);
  EXPECT_EQ(scene_to_ini(parse_scene(in, "resolved", {})), ini);
  EXPECT_NE(ini.find("restitution_law = tc_model"), std::string::npos);
}

template <class T>
class GasStart : public ::testing::Test {};
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(GasStart, Dims);

// [model §5]: the packing fraction exactly, zero momentum, exactly the temperature, no overlap,
// all inside the box; the seed picks the vacancies and velocities.
TYPED_TEST(GasStart, LatticeAtPhiWithZeroMomentumAndTheTemperatureNoOverlap) {
  constexpr int D = TypeParam::kDim;
  Scene s;
  s.kind = SceneKind::kGas;
  s.dimension = D;
  s.gas.phi = D == 3 ? 0.45 : 0.6;
  s.gas.grains = 1000;  // not a full lattice: random vacancies
  s.gas.temperature = 2.5;
  const Particles<D> p = build_initial_state<D>(s);
  const GasLattice<D> lattice = gas_lattice<D>(s.gas);
  ASSERT_EQ(p.size(), 1000u);
  EXPECT_NEAR(1000 * Dim<D>::volume(0.5) / lattice.box.prod(), s.gas.phi, 1e-12);
  Vec<D> momentum = Vec<D>::Zero();
  double sum_v2 = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    momentum += p.velocity()[i];
    sum_v2 += p.velocity()[i].squaredNorm();
    EXPECT_TRUE((p.position()[i].array() >= 0.0).all() &&
                (p.position()[i].array() < lattice.box.array()).all());
  }
  EXPECT_LT(momentum.norm(), 1e-12);
  EXPECT_NEAR(sum_v2 / (D * 1000.0), 2.5, 1e-12);
  EXPECT_GE(lattice.nearest, 1.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      Vec<D> dr = p.position()[i] - p.position()[j];
      for (int a = 0; a < D; ++a) dr[a] -= lattice.box[a] * std::nearbyint(dr[a] / lattice.box[a]);
      ASSERT_GE(dr.norm(), lattice.nearest * (1.0 - 1e-12));
    }
  s.run.seed = 2;
  EXPECT_NE(build_initial_state<D>(s).velocity()[0], p.velocity()[0]);
}

}  // namespace
}  // namespace granjet
