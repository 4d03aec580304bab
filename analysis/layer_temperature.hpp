// FE.1's measure (model §7): the granular temperature of the 2D jet's flowing grains in layer
// (a) just below the axis, T_g = sum m |v - <v>|^2 / (2 N) over the grains with centres at
// 0 < h <= analysis.layer_height above the height origin and -dy < y < 0, dy = R_tar/5 (one
// lateral bin). Bursts in the flow show up as its spikes.
#pragma once

#include "core/particles.hpp"
#include "core/scene.hpp"

namespace granjet::analysis {

// NaN with fewer than two grains there; `count`, when given, receives N.
double layer_a_temperature(const Particles<2>& p, const Scene& scene, int* count = nullptr);

}  // namespace granjet::analysis
