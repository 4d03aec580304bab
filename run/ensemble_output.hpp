// An ensemble's outputs, written the same way by `granjet run --seeds` and by campaigns: the
// ensemble file (analysis/ensemble_file.hpp) of the member runs that hold an analysis, and its
// JSON summary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

namespace granjet {

struct EnsembleMember {
  std::uint64_t seed = 0;
  std::filesystem::path output;  // the member's run file
};

// The file of one seed's run: run.h5 -> run.seed7.h5 (run.json -> run.seed7.json); empty stays
// empty.
std::filesystem::path member_file(const std::filesystem::path& file, std::uint64_t seed);

// `header` (scene, backend, dimension) opens the summary JSON, which then lists the members and
// holds the combined analysis; an empty `summary` writes none. Members without a stored analysis
// (a blown-up run, a window that never started) are left out. Returns how many members were
// combined; with none, nothing is written.
int merge_ensemble(const std::filesystem::path& out_file, const std::filesystem::path& summary,
                   nlohmann::json header, const std::vector<EnsembleMember>& members,
                   int dimension);

// Writes JSON next to its final name and renames it, so a reader never sees half a file.
void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace granjet
