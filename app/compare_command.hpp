// `granjet compare`: one scene on every backend, each with its own output and summary, and the
// summaries side by side (wall time, rates, energy balance, the measured quantities).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace granjet {

struct CompareOptions {
  std::filesystem::path scene_file;
  std::vector<std::string> overrides;  // "section.key=value"
  std::filesystem::path out_dir;       // gets BACKEND.h5, BACKEND.json, compare.json
  bool quiet = false;
};

// Returns 0, or 3 when a backend blew up (its output kept as .partial, the comparison still
// written). Throws InputError (exit 2) before any run when a backend cannot run the scene.
int compare_command(const CompareOptions& options, std::ostream& out);

}  // namespace granjet
