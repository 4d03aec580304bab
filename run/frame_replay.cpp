#include "run/frame_replay.hpp"

#include <sstream>
#include <string>
#include <vector>

#include "analysis/field_writer.hpp"
#include "analysis/file_lock.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/layer_temperature.hpp"
#include "analysis/run_analysis.hpp"
#include "core/dim.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

// The stored grains as a Particles store: jet grains have ids 0..jet.grains-1, the target's
// come after (core/initial_state); masses follow the scene's convention.
template <int D>
Particles<D> particles_of(const analysis::Frame<D>& frame, const Scene& scene) {
  Particles<D> p;
  for (std::size_t k = 0; k < frame.id.size(); ++k) {
    const bool wall = scene.kind == SceneKind::kJet && frame.id[k] >= scene.jet.grains;
    const GrainKind kind = wall ? GrainKind::kWall : GrainKind::kFree;
    p.add(frame.id[k], kind, frame.position[k], frame.velocity[k], frame.radius[k],
          grain_mass<D>(scene, kind, 2.0 * frame.radius[k]));
  }
  return p;
}

// The analysis of one run's stored frames in the window; `used` counts the frames in it.
template <int D>
analysis::RunResult analyse_frames(const std::filesystem::path& file,
                                   const std::optional<std::pair<double, double>>& window,
                                   std::size_t& used) {
  const analysis::FileSummary stored = analysis::read_summary(file);
  if (stored.dimension != D)
    throw InputError(file.string(), "holds " + std::to_string(stored.dimension) + "D grains, not " +
                                        std::to_string(D) + "D like the others");
  std::istringstream ini(stored.scene_ini);
  const Scene scene = parse_scene(ini, file.string() + " (stored scene)", {});
  analysis::AnalysisConfig config = analysis::AnalysisConfig::for_scene(scene);
  if (window) std::tie(config.window_start, config.window_end) = *window;
  // Every stored frame is a sample.
  if (scene.output.interval > 0.0) config.sample_interval = scene.output.interval;
  analysis::RunAnalysis<D> run(config);
  used = 0;
  for (std::size_t k = 0; k < stored.frames; ++k) {
    const analysis::Frame<D> frame = analysis::read_frame<D>(file, k);
    if (!run.due(frame.time)) continue;
    run.sample(frame.time, particles_of(frame, scene));
    used += run.in_window(frame.time);
  }
  if (used == 0)
    throw InputError("--window", file.string() + ": no stored frame lies in " +
                                     std::to_string(config.window_start) + ".." +
                                     std::to_string(config.window_end));
  return run.finish();
}

// The analysis goes into a copy of the file (without its earlier analysis), renamed over it when
// complete: a file that HDF5 can read but not extend (damaged), or a crash half-way, leaves the
// original as it was.
template <int D>
analysis::EnsembleResult store_into_copy(const std::filesystem::path& file,
                                         const std::vector<analysis::RunResult>& runs) {
  const std::filesystem::path copy = reanalysis_copy(file);
  const analysis::FileLock lock(copy);
  try {
    analysis::copy_without_analysis(file, copy);
    analysis::EnsembleResult result = analysis::write_ensemble(copy, runs, D, file);
    std::filesystem::rename(copy, file);
    return result;
  } catch (const std::exception& e) {
    std::filesystem::remove(copy);
    throw InputError(file.string(), std::string("cannot take its analysis (") + e.what() +
                                        "); the file is left as it was");
  }
}

template <int D>
Reanalysis reanalyse(const std::filesystem::path& file, const analysis::FileSummary& stored,
                     const std::optional<std::pair<double, double>>& window) {
  std::vector<std::filesystem::path> files{file};
  if (!stored.members.empty()) {
    files.clear();
    const std::filesystem::path here = file.parent_path();
    for (const std::string& member : stored.members) files.push_back(here / member);
  }
  std::vector<analysis::RunResult> runs;
  std::size_t frames = 0;
  for (const std::filesystem::path& f : files) {
    std::size_t used = 0;
    runs.push_back(analyse_frames<D>(f, window, used));
    frames += used;
  }
  return {store_into_copy<D>(file, runs), runs.size(), frames};
}

}  // namespace

std::filesystem::path reanalysis_copy(const std::filesystem::path& file) {
  std::filesystem::path copy = file;
  return copy += ".reanalysis";
}

TimeSeries layer_a_temperature_series(const std::filesystem::path& file) {
  const analysis::FileSummary stored = analysis::read_summary(file);
  if (stored.dimension != 2)
    throw InputError(file.string(), "layer (a) is the 2D jet's; this file holds 3D grains");
  std::istringstream ini(stored.scene_ini);
  const Scene scene = parse_scene(ini, file.string() + " (stored scene)", {});
  constexpr double kSlack = 1e-9;  // frame times are sums of output.interval
  TimeSeries series;
  for (std::size_t k = 0; k < stored.frames; ++k) {
    const analysis::Frame<2> frame = analysis::read_frame<2>(file, k);
    if (frame.time < scene.analysis.window_start - kSlack ||
        frame.time > scene.analysis.window_end + kSlack)
      continue;
    series.time.push_back(frame.time);
    series.value.push_back(analysis::layer_a_temperature(particles_of(frame, scene), scene));
  }
  return series;
}

Reanalysis reanalyse_frames(const std::filesystem::path& file,
                            const std::optional<std::pair<double, double>>& window) {
  const analysis::FileSummary stored = analysis::read_summary(file);
  return with_dimension(stored.dimension,
                        [&](auto d) { return reanalyse<d>(file, stored, window); });
}

}  // namespace granjet
