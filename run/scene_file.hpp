// Scene files: INI (Boost.Program_options config syntax) with `section.key = value` lines,
// every key overridable as `--set section.key=value`. One key table drives parsing,
// validation messages, the resolved INI stored in output files, and the help text.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace granjet {

// Reads a scene file and applies `overrides` ("section.key=value"). Throws InputError naming
// the file or key and what is allowed.
Scene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides);
Scene parse_scene(std::istream& in, const std::string& source,
                  const std::vector<std::string>& overrides);

// Cross-key checks (e.g. dt < t_c); parse_scene calls it.
void validate_scene(const Scene& scene);

// Every key with its resolved value, as a scene file that reproduces the run.
std::string scene_to_ini(const Scene& scene);

// "section.key  meaning (allowed values)" lines for --help.
std::string scene_keys_help();

}  // namespace granjet
