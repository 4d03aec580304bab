// The file of an ensemble of seeds (model §5: error bars are the spread over independent initial
// configurations): an H5MD file without frames, whose metadata are its first member's, that
// lists the member runs' files and holds /fields and /analysis combined over their stored
// analyses, with the fields' sidecar beside it.
#pragma once

#include <filesystem>
#include <vector>

#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

// Always a new file (never a merge into what was there), written as .partial and renamed when
// complete, like a run's file. `members` (at least one) must each hold an analysis
// (has_analysis); they are listed relative to the directory of `out_file`. Returns the combined
// result.
EnsembleResult write_ensemble_file(const std::filesystem::path& out_file,
                                   const std::vector<std::filesystem::path>& members,
                                   int dimension);

}  // namespace granjet::analysis
