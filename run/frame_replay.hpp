// Analysis after the run: the measurements of model §6 from the frames a file stores, a run's
// own or each member's of an ensemble file (combined over the seeds as `granjet run --seeds`
// does), written back into the file as /fields and /analysis with a .fields.xmf beside it.
// Stored frames hold no momentum transfers, so the contact stress (and P, mu*, I, eta) is left
// out (NaN); the inline analysis during a run measures everything.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "analysis/run_analysis.hpp"

namespace granjet {

struct Reanalysis {
  analysis::EnsembleResult result;
  std::size_t runs = 0;
  std::size_t frames = 0;  // the frames in the window, over all runs
};

// `window` replaces the stored scene's [analysis] window. The members of an ensemble are left
// as they are; the file is replaced only once its analysis is complete.
Reanalysis reanalyse_frames(const std::filesystem::path& file,
                            const std::optional<std::pair<double, double>>& window);

// The copy of `file` that reanalyse_frames writes and renames over it: FILE.reanalysis, never a
// run's FILE.partial, which `granjet resume` may still need.
std::filesystem::path reanalysis_copy(const std::filesystem::path& file);

// FE.1's T_g(t) in layer (a) (analysis/layer_temperature.hpp) over a 2D jet's stored frames
// inside its scene's analysis window; NaN where fewer than two grains are there. Throws
// InputError naming the file for a 3D one.
struct TimeSeries {
  std::vector<double> time;
  std::vector<double> value;
};
TimeSeries layer_a_temperature_series(const std::filesystem::path& file);

}  // namespace granjet
