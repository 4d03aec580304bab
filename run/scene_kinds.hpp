// What each scene kind is, in one entry: its word in scene.kind, what the run budget needs to
// know before anything is built (grains, lengths, the speed of its hardest contact, samples),
// what a quick run scales besides run.t_end, and the measurements that watch it. A new kind is
// a new entry here, its plain-data section in core/scene.hpp, its keys in run/scene_file.cpp
// and its initial state in core/initial_state.cpp.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "analysis/run_observer.hpp"
#include "core/scene.hpp"

namespace granjet {

// A number the budget bounds, with the key that sets it and what it is, for the message.
struct SceneQuantity {
  double value;
  std::string key;
  std::string what;
};

struct SceneKindTraits {
  SceneKind kind;
  std::string word;
  // Its measurement looks at every time step, on any backend (the budget counts the steps even
  // of an event-driven run).
  bool sampled_every_step;
  // The grains it starts with (an estimate for a 3D target's disk).
  double (*grains)(const Scene&);
  // Lattice sites drawn to build it (0: none), and its lengths in d.
  SceneQuantity (*sites)(const Scene&);
  std::vector<SceneQuantity> (*lengths)(const Scene&);
  // The relative normal speed of its hardest head-on contact.
  SceneQuantity (*contact_speed)(const Scene&);
  // Samples its measurements take over the run (0: none).
  SceneQuantity (*samples)(const Scene&);
  // The times besides run.t_end that a quick run (campaign --quick) scales with it, by key.
  std::vector<std::pair<std::string, double>> (*scaled_times)(const Scene&);
  // Its measurements, each an observer of the run, built on the simulator at the run's start.
  std::vector<std::unique_ptr<analysis::RunObserver<2>>> (*measurements_2d)(const Scene&,
                                                                            Simulator<2>&);
  std::vector<std::unique_ptr<analysis::RunObserver<3>>> (*measurements_3d)(const Scene&,
                                                                            Simulator<3>&);
};

const std::vector<SceneKindTraits>& scene_kinds();
const SceneKindTraits& scene_kind(SceneKind kind);

template <int D>
std::vector<std::unique_ptr<analysis::RunObserver<D>>> scene_measurements(const Scene& scene,
                                                                          Simulator<D>& sim) {
  if constexpr (D == 2)
    return scene_kind(scene.kind).measurements_2d(scene, sim);
  else
    return scene_kind(scene.kind).measurements_3d(scene, sim);
}

}  // namespace granjet
