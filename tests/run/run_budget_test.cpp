// The run budget (run/run_budget): every shipped scene passes on both backends, and each value
// that used to hang, exhaust memory or blow up at step 0 is refused naming its key.
#include "run/run_budget.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "run/scene_file.hpp"
#include "run/scene_kinds.hpp"

namespace granjet {
namespace {

const std::string kScenes = GRANJET_SCENES_DIR;
constexpr double kMachine = 16e9;  // bytes: a modest workstation

void expect_refused(const std::string& scene, const std::vector<std::string>& overrides,
                    const std::string& backend, const std::string& key, const std::string& what,
                    double memory = kMachine) {
  const Scene s = load_scene(kScenes + "/" + scene, overrides);
  try {
    check_run_budget(s, backend, memory);
    ADD_FAILURE() << overrides.front() << " passed the budget";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(RunBudget, ShippedScenesPassOnBothBackends) {
  for (const auto& entry : std::filesystem::directory_iterator(kScenes))
    for (const char* backend : {"soft_dem", "event_driven"})
      EXPECT_NO_THROW(check_run_budget(load_scene(entry.path(), {}), backend, kMachine))
          << entry.path() << " " << backend;
}

TEST(RunBudget, MemoryIsEstimatedFromTheGrainsAndNamesTheirKey) {
  // 20,000 jet grains and a 22 d hexagonal target of about 440 grains.
  const Scene jet = load_scene(kScenes + "/jet3d.ini", {});
  EXPECT_NEAR(scene_kind(jet.kind).grains(jet), 20000 + 439, 10);
  expect_refused("jet3d.ini", {}, "soft_dem", "jet.grains", "GB; this machine has", 1e7);
  expect_refused("jet3d.ini", {"jet.grains=100000000"}, "soft_dem", "jet.grains",
                 "grains would need");
  expect_refused("jet3d.ini", {"wall.diameter=100000"}, "soft_dem", "wall.diameter",
                 "grains would need");
  expect_refused("gas3d.ini", {"gas.grains=100000000"}, "event_driven", "gas.grains",
                 "grains would need");
}

TEST(RunBudget, ValuesThatHungAreRefusedWithTheirCount) {
  expect_refused("jet3d.ini", {"jet.phi_tilde=1e-308"}, "soft_dem", "jet.phi_tilde",
                 "lattice sites");
  expect_refused("jet3d.ini", {"jet.spacing=1e308"}, "soft_dem", "jet.spacing", "length");
  expect_refused("jet3d.ini", {"jet.gap=1e308"}, "soft_dem", "jet.gap", "at most 1e+07 d");
  expect_refused("binary.ini", {"binary.gap=1e9"}, "event_driven", "binary.gap", "at most 1e+07 d");
  expect_refused("gas3d.ini", {"gas.phi=1e-308"}, "event_driven", "gas.phi", "box edge");
  expect_refused("jet3d.ini", {"run.dt=1e-308"}, "soft_dem", "run.dt", "time steps");
  expect_refused("jet3d.ini", {"run.t_end=1e12"}, "soft_dem", "run.t_end", "time steps");
  expect_refused("binary.ini", {"run.dt=1e-12"}, "event_driven", "run.dt", "time steps");
  expect_refused("jet3d.ini", {"output.interval=1e-17"}, "soft_dem", "output.interval", "frames");
  expect_refused("jet3d.ini", {"run.progress_interval=1e-17"}, "event_driven",
                 "run.progress_interval", "progress rows");
  expect_refused("gas3d.ini", {"gas.sample_interval=1e-17"}, "event_driven", "gas.sample_interval",
                 "temperature samples");
  expect_refused("jet3d.ini", {"analysis.sample_interval=1e-17"}, "soft_dem",
                 "analysis.sample_interval", "analysis samples");
  // Enskog: about 3e4 collisions per unit time at phi 0.3, T = 1; 1e160 at T = 1e308.
  expect_refused("gas3d.ini", {"gas.temperature=1e308"}, "event_driven", "gas.temperature",
                 "collisions");
}

// 22 frames (every 5 of 100, and the last) of 20,439 grains, 72 bytes each (id, present,
// radius, position, velocity): 0.032 GB; with contacts (up to 3 a grain, 72 bytes each) 288
// bytes a grain: 0.13 GB.
TEST(RunBudget, OutputBytesAboveTheLimitAreRefusedUnlessRaised) {
  expect_refused("jet3d.ini", {"output.max_bytes=1e7"}, "soft_dem", "output.max_bytes",
                 "22 frames of 20439");
  EXPECT_NO_THROW(check_run_budget(load_scene(kScenes + "/jet3d.ini", {"output.max_bytes=4e7"}),
                                   "soft_dem", kMachine));
  expect_refused("jet3d.ini",
                 {"output.max_bytes=4e7", "output.fields=position,velocity,radius,id,contacts"},
                 "soft_dem", "output.max_bytes", "about 0.129");
}

// [3.1]: a linear contact at normal speed v overlaps by at most v t_c / pi; beyond
// run.max_overlap of the radius the soft DEM would blow up at step 0, so the scene is refused
// first.
TEST(RunBudget, SoftContactsTooFastForTheirContactTimeAreRefused) {
  // rms relative speed sqrt(2 D T) = sqrt(600) = 24.5: overlap 0.78 d > 0.25 d.
  expect_refused("gas3d.ini", {"gas.temperature=100"}, "soft_dem", "gas.temperature", "0.779");
  expect_refused("jet3d.ini", {"jet.speed=10"}, "soft_dem", "jet.speed", "overlaps by 0.318");
  expect_refused("binary.ini", {"binary.speed=10"}, "soft_dem", "binary.speed", "overlaps");
  // Hard spheres have no contact time: the same scene is fine on the event-driven backend.
  EXPECT_NO_THROW(check_run_budget(load_scene(kScenes + "/jet3d.ini", {"jet.speed=10"}),
                                   "event_driven", kMachine));
}

}  // namespace
}  // namespace granjet
