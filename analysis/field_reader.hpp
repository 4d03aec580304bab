// Reads one run's measurements back from the /fields and /analysis groups that
// write_analysis_hdf5 stored in its file (an ensemble of one seed), so that runs made by separate
// processes (`granjet run --seeds`, campaigns) are combined over their seeds from their files:
//
//   std::vector<RunResult> runs;
//   for (const auto& file : member_files) runs.push_back(read_run_result(file));
//   EnsembleResult all = combine_runs(runs, dimension);
//
// The values come back bit for bit (an ensemble of one stores each value as its mean); the
// columns come back in name order, which no consumer depends on.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/run_analysis.hpp"

namespace granjet::analysis {

// Throws std::runtime_error naming the file when it has no analysis of exactly one run.
RunResult read_run_result(const std::filesystem::path& file);

// One dataset of doubles (any shape, flattened row-major), e.g. "/fields/stress/rz/mean": for
// tools and tests. Throws std::runtime_error naming the file and dataset when it is missing.
std::vector<double> read_analysis_values(const std::filesystem::path& file,
                                         const std::string& dataset);

// The same with its shape (empty for a scalar), for bindings that hand out arrays.
struct ShapedValues {
  std::vector<std::size_t> shape;
  std::vector<double> values;
};
ShapedValues read_shaped_values(const std::filesystem::path& file, const std::string& dataset);

// The datasets below `group` (e.g. "/fields", "/observables"), by path relative to it
// ("stress/rz/mean"), in name order. Throws InputError naming the file when `group` is missing.
std::vector<std::string> list_datasets(const std::filesystem::path& file, const std::string& group);

// Whether the file holds a stored analysis (/fields and /analysis); false for a missing file.
bool has_analysis(const std::filesystem::path& file);

}  // namespace granjet::analysis
