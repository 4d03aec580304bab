// Runs that are valid but would end "complete" having measured nothing: granjet says so on
// stderr and in the summary's "warnings" before it runs, rather than let a user find out from
// empty results.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"
#include "run/backend_factory.hpp"

namespace granjet {

// `scene` as the backend resolved it.
std::vector<std::string> run_warnings(const Scene& scene, const Backend& backend);

}  // namespace granjet
