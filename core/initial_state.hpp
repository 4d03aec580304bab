// Builds the initial grains of a scene [spec §4-§5]: the jet lattice with random site removal,
// the target wall layer, or the two grains of the binary scene.
#pragma once

#include "core/particles.hpp"
#include "core/scene.hpp"

namespace granjet {

// The jet travels along -e_z (3D) or -e_x (2D) towards target grains centred in the plane
// z = 0 (x = 0). Jet grains get ids 0..N-1, wall grains N.. . Tethered wall grains have mass
// m, fixed ones infinite mass (inverse mass 0).
template <int D>
Particles<D> build_initial_state(const Scene& scene);

extern template Particles<2> build_initial_state<2>(const Scene&);
extern template Particles<3> build_initial_state<3>(const Scene&);

}  // namespace granjet
