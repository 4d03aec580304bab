// What the event-driven backend makes of a scene, decided once before a run [spec §8]. It runs
// every scene kind and refuses nothing: the soft-contact settings have no hard-core meaning and
// are ignored, a tethered target becomes fixed wall grains (spec §4), a plate target stays a
// plate (event_driven/plate.hpp), and a jet lattice whose grains touch is spaced by 1e-3 d (hard
// grains in contact collide infinitely often at once when the jet hits the target: their
// collision order is undefined).
#pragma once

#include <string>

#include "core/scene.hpp"

namespace granjet::ed {

// The smallest lattice spacing of a jet run by the event-driven backend, in d.
inline constexpr double kMinJetSpacing = 1.001;

// The scene as the backend runs it.
Scene hard_scene(const Scene& scene);

// The one-line note that says what changed and what is ignored, naming the keys.
std::string scene_note(const Scene& scene);

}  // namespace granjet::ed
