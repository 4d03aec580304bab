#include "analysis/inline_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "analysis/analysis_json.hpp"
#include "analysis/field_writer.hpp"

namespace granjet::analysis {

template <int D>
InlineAnalysis<D>::InlineAnalysis(const Scene& scene, Simulator<D>& sim)
    : analysis_(AnalysisConfig::for_scene(scene)), half_step_(0.5 * scene.dt()), sim_(&sim) {
  // The event-driven backend keeps impulses only when asked: from the start, so that a run
  // resumed inside the window counts them from its checkpoint (observe() turns this off
  // outside the window).
  sim.record_transfers(true);
}

template <int D>
double InlineAnalysis<D>::next_time(const Simulator<D>& sim) const {
  return std::max(analysis_.next_sample_time(), sim.time() + half_step_);
}

template <int D>
void InlineAnalysis<D>::observe(Simulator<D>& sim) {
  if (!analysis_.due(sim.time())) return;
  const auto start = std::chrono::steady_clock::now();
  const double time = sim.time();
  // Only the window's samples use transfers, each those since the previous sample: the window's
  // first sample starts the count, and outside the window none is recorded (the event-driven
  // backend's every impulse).
  sim.record_transfers(analysis_.in_window(time));
  // The scattered grains come to rank 0. A grain first found scattered now was within
  // region.beyond at the last sample, which looked at every grain beyond it, and has moved no
  // farther than the travel since: the grains beyond that were all counted then, and need not
  // come again. The first sample of a run, or after a resume, looks at them all.
  SampleRegion scattered = analysis_.scatter_region();
  const double travel = sim.travel();
  if (std::isfinite(travel - travel_at_sample_))
    scattered.until = scattered.beyond + (travel - travel_at_sample_);
  analysis_.observe_scattering(time, sim.particles_in(scattered));
  travel_at_sample_ = travel;
  // The bins' grains and transfers: over ranks each rank sums its own, joined at checkpoints
  // and at the end (join_samples).
  if (const std::optional<double> elapsed = analysis_.book_window(time, true))
    sim.sample_own(analysis_.bins_region(), *elapsed, analysis_.bins());
  analysis_.schedule_after(time);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <int D>
std::string InlineAnalysis<D>::store(const std::filesystem::path& file,
                                     const std::filesystem::path& published_as,
                                     nlohmann::json& summary) {
  if (!window_sampled()) return "no fields written: the analysis window never started";
  sim_->join_samples(analysis_.bins());
  const std::vector<RunResult> runs{finish()};
  summary["analysis"] = to_json(write_ensemble(file, runs, D, published_as));
  summary["analysis"]["seconds"] = seconds_;
  return {};
}

template class InlineAnalysis<2>;
template class InlineAnalysis<3>;

}  // namespace granjet::analysis
