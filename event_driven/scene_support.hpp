// What the event-driven backend makes of a scene [model §8], declared once before a run
// (core/scene_support.hpp). It runs every scene kind. It refuses output.fields that hard
// spheres do not have: force and contacts (they exchange impulses only) and omega (smooth hard
// spheres do not turn). It adapts two keys: a tethered target becomes fixed wall grains
// (model §4), and a jet lattice whose grains touch is spaced by 1e-3 d (hard grains in contact
// collide infinitely often at once when the jet hits the target: their collision order is
// undefined). A plate target stays a plate (event_driven/plate.hpp). The soft-contact settings
// have no hard-core meaning and are ignored.
#pragma once

#include "core/scene.hpp"
#include "core/scene_support.hpp"

namespace granjet::ed {

// The smallest lattice spacing of a jet run by the event-driven backend, in d.
inline constexpr double kMinJetSpacing = 1.001;

SceneSupport scene_support(const Scene& scene);

// The scene as the backend runs it: scene_support(scene).resolved.
Scene hard_scene(const Scene& scene);

}  // namespace granjet::ed
