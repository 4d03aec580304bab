// `granjet analyze run.h5 [--window t0:t1] [--summary out.json]`: the measurements of model §6
// from the frames stored in a run file. Stored frames hold no momentum transfers, so the
// contact stress (and what is built on it: P, mu*, I, eta) is left out (NaN); inline analysis
// during `granjet run` measures everything.
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
