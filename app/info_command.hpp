// `granjet info FILE [--scene]`: what a run's or an ensemble's file holds (creator, backend,
// status, frames, checkpoint, members), or with --scene the stored, fully resolved scene.
#pragma once

#include <filesystem>
#include <iosfwd>

namespace granjet {

struct InfoOptions {
  std::filesystem::path file;
  bool scene_only = false;
};

// Returns the exit code.
int info_command(const InfoOptions& options, std::ostream& out);

}  // namespace granjet
