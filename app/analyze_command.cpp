#include "app/analyze_command.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "analysis/analysis_json.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/run_analysis.hpp"
#include "app/scene_file.hpp"
#include "core/errors.hpp"

namespace granjet {
namespace {

// The stored grains as a Particles store: jet grains have ids 0..jet.grains-1, the target's
// come after (core/initial_state); masses follow the scene's convention.
template <int D>
Particles<D> particles_of(const analysis::Frame<D>& frame, const Scene& scene) {
  Particles<D> p;
  for (std::size_t k = 0; k < frame.id.size(); ++k) {
    const bool wall = scene.kind == SceneKind::kJet && frame.id[k] >= scene.jet.grains;
    double mass = 1.0;
    if (wall && scene.wall.kind == WallKind::kFixed)
      mass = std::numeric_limits<double>::infinity();
    else if (!wall && scene.jet.mass_by_volume)
      mass = std::pow(2.0 * frame.radius[k], D);
    p.add(frame.id[k], wall ? GrainKind::kWall : GrainKind::kFree, frame.position[k],
          frame.velocity[k], frame.radius[k], mass);
  }
  return p;
}

template <int D>
int analyze(const AnalyzeOptions& options, const analysis::FileSummary& stored,
            const Scene& scene, std::ostream& out) {
  analysis::AnalysisConfig config = analysis::AnalysisConfig::for_scene(scene);
  if (options.window) std::tie(config.window_start, config.window_end) = *options.window;
  // Every stored frame is a sample.
  if (scene.output.interval > 0.0) config.sample_interval = scene.output.interval;
  analysis::RunAnalysis<D> run(config);
  std::size_t used = 0;
  for (std::size_t k = 0; k < stored.frames; ++k) {
    const analysis::Frame<D> frame = analysis::read_frame<D>(options.file, k);
    if (!run.due(frame.time)) continue;
    run.sample(frame.time, particles_of(frame, scene));
    used += run.in_window(frame.time);
  }
  if (used == 0)
    throw InputError("--window", "no stored frame lies in " + std::to_string(config.window_start) +
                                     ".." + std::to_string(config.window_end));
  const std::vector<analysis::RunResult> runs{run.finish()};
  const analysis::EnsembleResult result = analysis::combine_runs(runs, D);
  const std::filesystem::path xmf = analysis::store_ensemble(options.file, result);
  out << "analysed " << used << " frames in " << config.window_start << ".." << config.window_end
      << "; wrote /fields and /analysis into " << options.file.string() << " and "
      << xmf.string() << "\n";
  if (!options.summary.empty()) {
    std::ofstream f(options.summary);
    if (!f) throw std::runtime_error("cannot write the summary " + options.summary.string());
    f << analysis::to_json(result).dump(2) << "\n";
  }
  return 0;
}

}  // namespace

int analyze_command(const AnalyzeOptions& options, std::ostream& out) {
  const analysis::FileSummary stored = analysis::read_summary(options.file);
  if (options.window && !(options.window->second > options.window->first))
    throw InputError("--window", "expected t0:t1 with t1 > t0");
  std::istringstream ini(stored.scene_ini);
  const Scene scene = parse_scene(ini, options.file.string() + " (stored scene)", {});
  return stored.dimension == 2 ? analyze<2>(options, stored, scene, out)
                               : analyze<3>(options, stored, scene, out);
}

}  // namespace granjet
