// Runs that are valid but would end "complete" having measured nothing: granjet says so on
// stderr and in the summary's "warnings" before it runs, rather than let a user find out from
// empty results.
#pragma once

#include <string>
#include <vector>

#include "core/scene.hpp"

namespace granjet {

std::vector<std::string> run_warnings(const Scene& scene, const std::string& backend);

}  // namespace granjet
