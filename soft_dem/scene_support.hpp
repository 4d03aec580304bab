// What the soft-sphere DEM backend makes of a scene (core/scene_support.hpp). It runs every
// scene as it is and adapts nothing; it refuses a contact.model in a dimension the law does not
// support and omega in output.fields when the grains cannot turn (contact.friction = 0: no
// tangential force), and advises against time steps coarser than 0.05 t_c.
#pragma once

#include "core/scene.hpp"
#include "core/scene_support.hpp"

namespace granjet::dem {

SceneSupport scene_support(const Scene& scene);

// Throws InputError unless the soft DEM can spread `scene` over `ranks` MPI ranks (more than
// one): the domain decomposition cuts open space, so a periodic box (the gases) runs on one.
void check_over_ranks(const Scene& scene, int ranks);

}  // namespace granjet::dem
