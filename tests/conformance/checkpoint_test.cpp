// Checkpoints: a simulator built anew from the scene that restores a checkpoint goes
// on bit-identically to the one that wrote it, on both backends, both integrators, friction on
// and off, tethered, fixed and plate targets, a periodic gas, 1 and 2 threads, both soft contact
// laws, and a resume of a resume.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "analysis/analysis_json.hpp"
#include "analysis/gas_observer.hpp"
#include "analysis/inline_analysis.hpp"
#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

struct Case {
  std::string name;
  std::string scene;  // a shipped scene
  std::string backend;
  std::vector<std::string> overrides;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// The grains' state in id order, every number exact.
template <int D>
struct State {
  std::vector<GrainId> id;
  std::vector<Vec<D>> x, v;
  std::vector<Spin<D>> w;
  EnergyBalance e;
  SimStats s;

  explicit State(const Simulator<D>& sim) : e(sim.energy()), s(sim.stats()) {
    const Particles<D>& p = sim.particles();
    std::vector<std::size_t> order(p.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return p.id()[a] < p.id()[b]; });
    for (std::size_t k : order) {
      id.push_back(p.id()[k]);
      x.push_back(p.position()[k]);
      v.push_back(p.velocity()[k]);
      w.push_back(p.spin()[k]);
    }
  }
};

template <int D>
void expect_identical(const State<D>& a, const State<D>& b, const std::string& what) {
  ASSERT_EQ(a.id, b.id) << what;
  std::size_t differ = 0;
  for (std::size_t k = 0; k < a.id.size(); ++k)
    differ += a.x[k] != b.x[k] || a.v[k] != b.v[k] || a.w[k] != b.w[k];
  EXPECT_EQ(differ, 0u) << what << ": grains whose state differs";
  EXPECT_EQ(a.e.kinetic, b.e.kinetic) << what;
  EXPECT_EQ(a.e.dissipated, b.e.dissipated) << what;
  EXPECT_EQ(a.e.removed, b.e.removed) << what;
  EXPECT_EQ(a.s.steps, b.s.steps) << what;
  EXPECT_EQ(a.s.events, b.s.events) << what;
  EXPECT_EQ(a.s.collisions, b.s.collisions) << what;
  EXPECT_EQ(a.s.removed, b.s.removed) << what;
}

template <int D>
void check(const Case& c, const Scene& scene, double t1, double t2, double t3) {
  // Straight: checkpoints at t1 and t2 (a checkpoint is part of the run), on to t3.
  auto straight = make_simulator<D>(c.backend, scene);
  StateArchive at_t1, at_t2;
  straight->advance_to(t1);
  straight->checkpoint(at_t1);
  straight->advance_to(t2);
  straight->checkpoint(at_t2);
  straight->advance_to(t3);
  const State<D> expected(*straight);
  ASSERT_GT(expected.s.collisions + expected.s.steps, 0);

  // Resumed at t1 on one thread (the soft DEM's case with two threads checks that the count
  // does not matter), checkpointed at t2 and that checkpoint resumed in turn.
  Scene one_thread = scene;
  one_thread.run.threads = 1;
  auto resumed = make_simulator<D>(c.backend, one_thread);
  resumed->restore(at_t1);
  resumed->advance_to(t2);
  StateArchive again;
  resumed->checkpoint(again);
  resumed->advance_to(t3);
  expect_identical(expected, State<D>(*resumed), c.name + ": resumed at t1");
  auto twice = make_simulator<D>(c.backend, scene);
  twice->restore(again);
  twice->advance_to(t3);
  expect_identical(expected, State<D>(*twice), c.name + ": resumed at t1, then at t2");
}

class Checkpoint : public ::testing::TestWithParam<Case> {};

TEST_P(Checkpoint, ResumedRunIsBitIdenticalToTheStraightRun) {
  const Case& c = GetParam();
  std::vector<std::string> overrides = c.overrides;
  const Scene probe = load_scene(std::string(GRANJET_SCENES_DIR) + "/" + c.scene, overrides);
  if (probe.kind == SceneKind::kJet)
    overrides.insert(overrides.begin(), {"jet.grains=600", "run.t_end=8"});
  else
    overrides.insert(overrides.begin(), {"gas.grains=256", "run.t_end=8", "gas.equilibration=1"});
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/" + c.scene, overrides);
  // The jet meets the target at t ~ 1: checkpoints in the thick of the impact.
  if (scene.dimension == 2)
    check<2>(c, scene, 2.0, 3.5, 5.0);
  else
    check<3>(c, scene, 2.0, 3.5, 5.0);
}

INSTANTIATE_TEST_SUITE_P(
    BothBackends, Checkpoint,
    ::testing::Values(
        Case{"dem_jet3d_ab2_friction_tethered", "jet3d.ini", "soft_dem", {}},
        Case{"dem_jet3d_verlet", "jet3d.ini", "soft_dem", {"run.integrator=verlet"}},
        Case{"dem_jet3d_frictionless_fixed",
             "jet3d.ini",
             "soft_dem",
             {"contact.friction=0", "wall.kind=fixed"}},
        Case{"dem_jet3d_plate_threads2",
             "jet3d.ini",
             "soft_dem",
             {"wall.kind=plate", "run.threads=2"}},
        Case{"dem_jet2d_bidisperse", "jet2d.ini", "soft_dem", {}},
        Case{"dem_jet3d_hertz_plate",
             "jet3d.ini",
             "soft_dem",
             {"contact.model=hertz", "wall.kind=plate"}},
        Case{"dem_gas3d_periodic", "hcs3d.ini", "soft_dem", {}},
        Case{"ed_jet3d", "jet3d.ini", "event_driven", {}},
        Case{"ed_jet2d_tc_model", "jet2d.ini", "event_driven", {"ed.restitution_law=tc_model"}},
        Case{"ed_jet3d_plate", "jet3d.ini", "event_driven", {"wall.kind=plate"}},
        Case{"ed_gas3d_periodic", "gas3d.ini", "event_driven", {}},
        Case{"ed_hcs2d_periodic", "hcs2d.ini", "event_driven", {}}),
    [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

// The inline analysis of a run as the app drives it, from t = 0 (or a checkpoint) to t_end.
template <int D>
void drive(Simulator<D>& sim, analysis::InlineAnalysis<D>& fields, double t_end) {
  while (sim.time() < t_end - 1e-9) {
    sim.advance_to(std::min(t_end, fields.next_time(sim)));
    fields.observe(sim);
  }
}

// The analysis' sums go into the checkpoint with the simulator's state: the resumed run's
// fields, scattering and velocity distributions are the straight run's, every digit.
template <int D>
void check_analysis(const std::string& backend, const Scene& scene) {
  auto straight = make_simulator<D>(backend, scene);
  analysis::InlineAnalysis<D> straight_fields(scene, *straight);
  drive(*straight, straight_fields, 2.0);
  ASSERT_TRUE(straight_fields.window_sampled());  // the checkpoint falls inside the window
  StateArchive archive;
  straight->checkpoint(archive);
  StateWriter writer(archive, "analysis");
  straight_fields.visit_state(writer);
  drive(*straight, straight_fields, scene.run.t_end);
  const std::vector<analysis::RunResult> expected{straight_fields.finish()};

  auto resumed = make_simulator<D>(backend, scene);
  analysis::InlineAnalysis<D> resumed_fields(scene, *resumed);
  resumed->restore(archive);
  StateReader reader(archive, "analysis");
  resumed_fields.visit_state(reader);
  drive(*resumed, resumed_fields, scene.run.t_end);
  const std::vector<analysis::RunResult> got{resumed_fields.finish()};
  EXPECT_EQ(analysis::to_json(analysis::combine_runs(got, D)).dump(),
            analysis::to_json(analysis::combine_runs(expected, D)).dump())
      << backend;
}

TEST(CheckpointAnalysis, ResumedInlineAnalysisIsBitIdentical) {
  const std::vector<std::string> small = {"jet.grains=800", "run.t_end=5",
                                          "analysis.window_start=1", "analysis.window_end=5",
                                          "analysis.sample_interval=0.25"};
  for (const char* backend : {"soft_dem", "event_driven"}) {
    check_analysis<3>(backend, load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini", small));
    check_analysis<2>(backend, load_scene(std::string(GRANJET_SCENES_DIR) + "/jet2d.ini", small));
  }
}

// The gas observer's sums (temperature, virial, the cooling fits) likewise.
TEST(CheckpointAnalysis, ResumedGasObserverIsBitIdentical) {
  const Scene scene = load_scene(
      std::string(GRANJET_SCENES_DIR) + "/hcs3d.ini",
      {"gas.grains=500", "run.t_end=4", "gas.equilibration=1", "gas.sample_interval=0.1"});
  const auto run = [&](Simulator<3>& sim, analysis::GasObserver<3>& gas, double t_end) {
    while (sim.time() < t_end - 1e-9) {
      sim.advance_to(std::min(t_end, gas.next_time(sim)));
      gas.observe(sim);
    }
  };
  auto straight = make_simulator<3>("event_driven", scene);
  analysis::GasObserver<3> straight_gas(scene, *straight);
  run(*straight, straight_gas, 2.0);
  StateArchive archive;
  straight->checkpoint(archive);
  StateWriter writer(archive, "gas");
  straight_gas.visit_state(writer);
  run(*straight, straight_gas, 4.0);

  auto resumed = make_simulator<3>("event_driven", scene);
  analysis::GasObserver<3> resumed_gas(scene, *resumed);
  resumed->restore(archive);
  StateReader reader(archive, "gas");
  resumed_gas.visit_state(reader);
  run(*resumed, resumed_gas, 4.0);
  ASSERT_GT(straight_gas.samples(), 10);
  EXPECT_EQ(resumed_gas.samples(), straight_gas.samples());
  EXPECT_EQ(resumed_gas.temperature(), straight_gas.temperature());
  EXPECT_EQ(resumed_gas.cooling_per_collision(), straight_gas.cooling_per_collision());
  EXPECT_EQ(resumed_gas.cooling_rate(1.0), straight_gas.cooling_rate(1.0));
}

}  // namespace
}  // namespace granjet
