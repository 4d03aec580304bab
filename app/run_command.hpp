// `granjet run`: one scene on one backend, with progress rows, H5MD output and a JSON summary.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace granjet {

struct RunOptions {
  std::filesystem::path scene_file;
  std::string backend = "soft_dem";
  std::vector<std::string> overrides;  // "section.key=value"
  std::filesystem::path out;           // empty: <scene file stem>.h5 in the working directory
  std::filesystem::path summary;       // empty: no JSON summary
  bool quiet = false;
};

// Returns the process exit code: 0 done, 3 blow-up (the output kept as .partial). Throws
// InputError (exit 2) for bad input before any file is written.
int run_command(const RunOptions& options, std::ostream& out);

}  // namespace granjet
