// The analysis sees only the Simulator interface: one small jet built by both backends gives the
// same kinetic fields for the same particle data (here the initial state, before either
// backend has moved a grain).
#include <gtest/gtest.h>

#include "analysis/run_analysis.hpp"
#include "app/backend_factory.hpp"

namespace granjet {
namespace {

analysis::Table kinetic_fields(const std::string& backend, const Scene& scene) {
  const auto sim = make_simulator<3>(backend, scene);
  const analysis::AnalysisConfig config = analysis::AnalysisConfig::for_scene(scene);
  analysis::FieldAccumulator<3> fields(config.bins);
  fields.sample(sim->particles(), {}, 0.0);
  return fields.fields(config.options);
}

TEST(BackendNeutralAnalysis, SameParticlesGiveTheSameKineticStressOnBothBackends) {
  Scene scene;
  scene.jet.grains = 600;
  scene.jet.gap = 0.2;      // the front row inside the first layer above the wall
  scene.jet.spacing = 1.05;  // not touching: the hard-core backend keeps the lattice as it is
  scene.contact.friction = 0.0;
  scene.wall.kind = WallKind::kFixed;
  const analysis::Table soft = kinetic_fields("soft_dem", scene);
  const analysis::Table hard = kinetic_fields("event_driven", scene);
  ASSERT_EQ(soft.rows(), hard.rows());
  double grains_seen = 0.0;
  for (std::size_t bin = 0; bin < soft.rows(); ++bin) {
    SCOPED_TRACE(bin);
    grains_seen += soft.at(bin, "n");
    for (const char* name : {"n", "phi", "stress_kinetic.zz", "stress_kinetic.rr", "v.z"}) {
      const double a = soft.at(bin, name), b = hard.at(bin, name);
      if (std::isnan(a)) {
        EXPECT_TRUE(std::isnan(b)) << name;
      } else {
        EXPECT_NEAR(a, b, 1e-12 * std::abs(a) + 1e-15) << name;
      }
    }
  }
  EXPECT_GT(grains_seen, 0.0);  // the comparison saw grains
}

}  // namespace
}  // namespace granjet
