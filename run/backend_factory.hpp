// The backends, each with what it declares (as OpenMM's platforms do): how it counts its work,
// and what it makes of a scene (core/scene_support.hpp): features it refuses, keys it adapts,
// what it ignores. The one place where a backend name becomes a Simulator.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/scene_support.hpp"
#include "core/simulator.hpp"

namespace granjet {

struct Backend {
  std::string name;
  // Event-driven: its work is events and collisions (progress rows, summary), not time steps
  // and contacts.
  bool counts_events = false;
  // One core's rate for campaign plans, a guide rather than a benchmark, rounded from what
  // `granjet run` reported for the shipped jets: particle-steps/s counting the grains present
  // (time-stepped) or grain-time units/s (event-driven), in 2D and 3D.
  double rate_2d = 0.0;
  double rate_3d = 0.0;
  // Memory per grain at its peak, for the run budget: measured 0.6-1 kB on jet3d and gas3d,
  // doubled for the contacts and lists of a dense pile.
  double bytes_per_grain = 0.0;
  // Soft grains: the deepest overlap of a head-on contact at relative normal speed v (the run
  // budget refuses scenes beyond run.max_overlap); null for hard grains, which never overlap.
  double (*peak_overlap)(const Scene& scene, double v) = nullptr;
  SceneSupport (*support)(const Scene& scene) = nullptr;
  // Its simulator of a scene it resolved.
  std::unique_ptr<Simulator<2>> (*make_2d)(const Scene& resolved) = nullptr;
  std::unique_ptr<Simulator<3>> (*make_3d)(const Scene& resolved) = nullptr;
};

std::vector<std::string> backend_names();

// Throws InputError naming --backend when no backend has the name.
const Backend& backend_named(const std::string& name);

// What the backend makes of the scene. Throws InputError naming --backend for an unknown
// backend, and naming the key of a feature it cannot run.
SceneSupport check_backend(const std::string& backend, const Scene& scene);

// One adaptation as a line for the user: "event_driven: wall.kind = tethered becomes fixed
// (why)".
std::string describe(const std::string& backend, const SceneSupport::Adaptation& adaptation);

// The backend's simulator of the scene as it resolves it (check_backend first).
template <int D>
std::unique_ptr<Simulator<D>> make_simulator(const std::string& backend, const Scene& scene);

extern template std::unique_ptr<Simulator<2>> make_simulator<2>(const std::string&, const Scene&);
extern template std::unique_ptr<Simulator<3>> make_simulator<3>(const std::string&, const Scene&);

}  // namespace granjet
