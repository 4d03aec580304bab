#include "app/analyze_command.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <sstream>

#include "analysis/analysis_json.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/file_lock.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/run_analysis.hpp"
#include "run/ensemble_output.hpp"
#include "run/scene_file.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"

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

// The analysis goes into a copy of the file, renamed over it when complete: a file that HDF5
// can read but not extend (damaged), or a crash half-way, leaves the original as it was.
template <int D>
analysis::EnsembleResult store_into_copy(const std::filesystem::path& file,
                                         const std::vector<analysis::RunResult>& runs) {
  std::filesystem::path copy = file;
  copy += ".partial";
  const analysis::FileLock lock(copy);
  std::filesystem::copy_file(file, copy, std::filesystem::copy_options::overwrite_existing);
  try {
    analysis::EnsembleResult result = analysis::write_ensemble(copy, runs, D, file);
    std::filesystem::rename(copy, file);
    return result;
  } catch (const std::exception& e) {
    std::filesystem::remove(copy);
    throw InputError(file.string(), std::string("cannot take its analysis (") + e.what() +
                                        "); the file is left as it was");
  }
}

// A run's file: its own frames. An ensemble's file (no frames): each member run's frames,
// combined over the seeds as `granjet run --seeds` does; the members are left as they are.
template <int D>
int analyze(const AnalyzeOptions& options, const analysis::FileSummary& stored, std::ostream& out) {
  std::vector<std::filesystem::path> files{options.file};
  if (!stored.members.empty()) {
    files.clear();
    const std::filesystem::path here = options.file.parent_path();
    for (const std::string& member : stored.members) files.push_back(here / member);
  }
  std::vector<analysis::RunResult> runs;
  std::size_t frames = 0;
  for (const std::filesystem::path& file : files) {
    std::size_t used = 0;
    runs.push_back(analyse_frames<D>(file, options.window, used));
    frames += used;
  }
  const analysis::EnsembleResult result = store_into_copy<D>(options.file, runs);
  out << "analysed " << frames << " frames of " << runs.size() << " run(s); wrote /fields and "
      << "/analysis into " << options.file.string() << " and "
      << analysis::fields_sidecar(options.file).string() << "\n";
  if (!options.summary.empty()) write_json_atomically(options.summary, analysis::to_json(result));
  return 0;
}

}  // namespace

int analyze_command(const AnalyzeOptions& options, std::ostream& out) {
  const analysis::FileSummary stored = analysis::read_summary(options.file);
  if (options.window && !(options.window->second > options.window->first))
    throw InputError("--window", "expected t0:t1 with t1 > t0");
  return with_dimension(stored.dimension, [&](auto d) { return analyze<d>(options, stored, out); });
}

}  // namespace granjet
