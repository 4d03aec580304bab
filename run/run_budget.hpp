// What a scene would cost, checked before anything is built or written: memory, time steps or
// collisions, frames, samples, progress rows, output bytes and the size of the scene in space.
// Each is refused above a limit with the number it came to and the key that sets it. Without
// this, a typo (run.dt = 1e-308, jet.phi_tilde = 1e-308, gas.grains = 2^63 - 1) hangs for hours
// or runs the machine out of memory instead of giving an error.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.hpp"

namespace granjet {

// Throws InputError naming the key (--backend for an unknown backend). What the backend declares
// (run/backend_factory.hpp) decides what counts: time steps or collisions, contact overlaps.
// `memory_bytes` is what the machine has (physical memory).
void check_run_budget(const Scene& scene, const std::string& backend, double memory_bytes);

// The machine's physical memory in bytes.
double physical_memory_bytes();

}  // namespace granjet
