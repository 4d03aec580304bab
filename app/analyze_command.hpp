// `granjet analyze run.h5 [--window t0:t1] [--summary out.json]`: the measurements of model §6
// from the frames a file stores (run/frame_replay.hpp), what was analysed printed, and the JSON.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <utility>

namespace granjet {

struct AnalyzeOptions {
  std::filesystem::path file;
  std::optional<std::pair<double, double>> window;  // default: the scene's [analysis] window
  std::filesystem::path summary;                    // empty: no JSON
};

// Writes /fields and /analysis into the file and a .fields.xmf beside it. Returns the exit code.
int analyze_command(const AnalyzeOptions& options, std::ostream& out);

}  // namespace granjet
