// The analysis sees only the Simulator interface: one small jet built by both backends gives the
// same kinetic fields for the same particle data (here the initial state, before either
// backend has moved a grain); and both backends' jets on a target narrower than the jet are
// measured from grains that have turned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/run_analysis.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"

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
  scene.jet.gap = 0.2;       // the front row inside the first layer above the wall
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

// F4.2 needs X = D_tar/D_jet = 0.5: a jet of D_jet = 4.5 d on a target of 2.25 d runs, and the
// scattering measurement's radius lies beyond the jet (its outer radius + 1 d, not 1.5 R_tar =
// 1.7 d, which is inside it). So nothing counts as scattered at t = 0, and every grain that
// psi0 is computed from has turned: its velocity has left the incident -e_z.
TEST(NarrowTarget, F4_2_JetWiderThanTheTargetIsMeasuredOnTurnedGrainsOnly) {
  const Scene scene =
      load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                 {"jet.diameter=4.5", "wall.diameter=2.25", "jet.grains=600", "run.t_end=12",
                  "analysis.window_start=6", "analysis.window_end=12"});
  const analysis::AnalysisConfig config = analysis::AnalysisConfig::for_scene(scene);
  EXPECT_DOUBLE_EQ(config.scatter_radius, 2.25 + 1.0);
  for (const std::string backend : {"soft_dem", "event_driven"}) {
    SCOPED_TRACE(backend);
    const auto sim = make_simulator<3>(backend, scene);
    sim->record_transfers(true);
    analysis::RunAnalysis<3> run(config);
    std::vector<PairImpulse<3>> transfers;
    while (sim->time() < scene.run.t_end - 1e-9) {
      sim->advance_to(std::min(run.next_sample_time(), scene.run.t_end));
      if (!run.due(sim->time())) continue;
      transfers.clear();
      sim->collect_transfers(transfers);
      run.sample(sim->time(), sim->particles(), transfers);
      if (sim->time() == 0.0) {
        EXPECT_EQ(run.scattering().count(), 0u);  // the jet as built
      }
    }
    ASSERT_GT(run.scattering().count(), 20u);
    for (const Vec<3>& v : run.scattering().velocities())
      EXPECT_GT(std::hypot(v.x(), v.y()), 1e-6 * v.norm()) << v.transpose();
    const double psi0 = run.scattering().psi0();
    EXPECT_GT(psi0, 0.3);
    EXPECT_LT(psi0, std::numbers::pi);
  }
}

}  // namespace
}  // namespace granjet
