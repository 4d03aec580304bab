// Full DEM steps on the shipped jets (Google Benchmark): particle-steps/s after impact.
#include <benchmark/benchmark.h>

#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace {

// Args: friction x 10, run.threads. Fixed wall, as in the LAMMPS peer inputs.
template <int D>
void BM_DemJetStep(benchmark::State& state) {
  const std::string file = std::string(GRANJET_SCENES_DIR) + (D == 3 ? "/jet3d.ini" : "/jet2d.ini");
  const granjet::Scene scene = granjet::load_scene(
      file, {"wall.kind=fixed", "contact.friction=" + std::to_string(state.range(0) / 10.0),
             "run.threads=" + std::to_string(state.range(1))});
  auto sim = granjet::dem::make_dem_simulator<D>(scene);
  sim->advance_to(20.0);  // the jet has hit the target: real contacts and rebuilds
  const double dt = scene.dt();
  const std::int64_t before = sim->stats().particle_steps;
  for (auto _ : state) sim->advance_to(sim->time() + 100 * dt);
  state.counters["particle_steps/s"] = benchmark::Counter(
      static_cast<double>(sim->stats().particle_steps - before), benchmark::Counter::kIsRate);
}

}  // namespace

// Wall time (UseRealTime): with threads the process' CPU time is not the cost.
BENCHMARK(BM_DemJetStep<3>)
    ->ArgsProduct({{2, 0}, {1, 2}})
    ->ArgNames({"mu_x10", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DemJetStep<2>)
    ->ArgsProduct({{2, 0}, {1, 2}})
    ->ArgNames({"mu_x10", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
