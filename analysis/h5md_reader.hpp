// Reads granjet H5MD files back: a summary for `granjet info` and single frames for analysis.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/particles.hpp"

namespace granjet::analysis {

struct FileSummary {
  std::string creator;
  std::string creator_version;
  std::string backend;
  std::string status;  // "running" (interrupted), "complete", or the reason the run was abandoned
  std::array<int, 2> h5md_version{};
  int dimension = 0;
  std::size_t frames = 0;
  std::size_t max_grains = 0;
  double first_time = 0.0;  // first/last frame; 0 without frames
  double last_time = 0.0;
  std::int64_t last_step = 0;
  std::size_t observable_rows = 0;
  std::string scene_ini;            // as the backend ran it
  std::string requested_scene_ini;  // where the backend adapted the scene; else empty
  // An ensemble file's member runs, relative to its directory; empty for a run's file.
  std::vector<std::string> members;
  // Whether the file is a run's .partial with a readable checkpoint beside it
  // (checkpoint_file.hpp): one that can be resumed.
  bool checkpoint = false;
  double checkpoint_time = 0.0;
};

// Throws std::runtime_error naming the file if it is not a granjet H5MD file.
FileSummary read_summary(const std::filesystem::path& file);
// One stored frame, only its valid grains, sorted by id.
template <int D>
struct Frame {
  std::int64_t step = 0;
  double time = 0.0;
  std::vector<GrainId> id;
  std::vector<Vec<D>> position;
  std::vector<Vec<D>> velocity;
  std::vector<double> radius;
};

// Frame `index` (0..frames-1). Throws std::runtime_error naming the file if it is not a granjet
// H5MD file of dimension D or has no such frame.
template <int D>
Frame<D> read_frame(const std::filesystem::path& file, std::size_t index);

extern template Frame<2> read_frame<2>(const std::filesystem::path&, std::size_t);
extern template Frame<3> read_frame<3>(const std::filesystem::path&, std::size_t);

}  // namespace granjet::analysis
