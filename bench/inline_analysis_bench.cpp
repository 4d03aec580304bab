// The inline analysis' share of a jet run: the shipped jets after impact,
// stepped one analysis.sample_interval at a time with (arg 1) and without (arg 0) the sample
// taken at its end — binned fields, stress from the momentum transfers. particle-steps/s; the
// ratio of the two is what the analysis costs.
#include <benchmark/benchmark.h>

#include <optional>

#include "analysis/inline_analysis.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace {

template <int D>
void BM_JetInlineAnalysis(benchmark::State& state) {
  const std::string file = std::string(GRANJET_SCENES_DIR) + (D == 3 ? "/jet3d.ini" : "/jet2d.ini");
  // The window opens once the jet has hit the target, so every sample bins and tallies.
  const granjet::Scene scene = granjet::load_scene(
      file, {"analysis.window_start=5", "analysis.window_end=1000", "run.t_end=1000"});
  auto sim = granjet::dem::make_dem_simulator<D>(scene);
  std::optional<granjet::analysis::InlineAnalysis<D>> analysis;
  if (state.range(0)) analysis.emplace(scene, *sim);
  sim->advance_to(5.0);
  if (analysis) analysis->observe(*sim);
  const std::int64_t before = sim->stats().particle_steps;
  for (auto _ : state) {
    sim->advance_to(sim->time() + scene.analysis.sample_interval);
    if (analysis) analysis->observe(*sim);
  }
  state.counters["particle_steps/s"] = benchmark::Counter(
      static_cast<double>(sim->stats().particle_steps - before), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_JetInlineAnalysis<3>)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("analysis")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JetInlineAnalysis<2>)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("analysis")
    ->Unit(benchmark::kMillisecond);
