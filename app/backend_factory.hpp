// The one place where a backend name becomes a Simulator.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/simulator.hpp"

namespace granjet {

std::vector<std::string> backend_names();

// Throws InputError naming --backend when the name is unknown, or naming the scene key the
// backend cannot run (the soft DEM: a contact.model in a dimension it does not support).
void check_backend(const std::string& backend, const Scene& scene);

// What the backend ignores or replaces in the scene, as lines for the user (may be empty).
std::vector<std::string> backend_notes(const std::string& backend, const Scene& scene);

// Calls check_backend first.
template <int D>
std::unique_ptr<Simulator<D>> make_simulator(const std::string& backend, const Scene& scene);

extern template std::unique_ptr<Simulator<2>> make_simulator<2>(const std::string&, const Scene&);
extern template std::unique_ptr<Simulator<3>> make_simulator<3>(const std::string&, const Scene&);

}  // namespace granjet
