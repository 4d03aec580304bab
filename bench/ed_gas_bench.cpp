// Event-driven collisions per second (Google Benchmark; collisions only, not cell crossings):
// the elastic 3D gas of N = 10,976 spheres at phi = 0.3 and 0.45 (the reference points;
// the backend's choice of search, and the cells alone to show what the neighbour lists buy) and
// the 2D jet after impact. The scene is built and equilibrated outside the timed loop.
#include <benchmark/benchmark.h>

#include "core/initial_state.hpp"
#include "event_driven/ed_simulator.hpp"
#include "event_driven/scene_support.hpp"
#include "run/scene_file.hpp"

namespace {

// Advances in chunks of `chunk` sim time; reports collisions/s.
template <int D>
void run(benchmark::State& state, std::unique_ptr<granjet::Simulator<D>> sim, double warm_up,
         double chunk) {
  sim->advance_to(warm_up);
  const granjet::SimStats before = sim->stats();
  for (auto _ : state) {
    sim->advance_to(sim->time() + chunk);
    benchmark::DoNotOptimize(sim->stats());
  }
  const granjet::SimStats after = sim->stats();
  const auto collisions = static_cast<double>(after.collisions - before.collisions);
  state.counters["collisions/s"] = benchmark::Counter(collisions, benchmark::Counter::kIsRate);
  // Per collision: the other events (cell crossings, stale predictions) that cost calendar work.
  state.counters["crossings/coll"] =
      static_cast<double>(after.cell_crossings - before.cell_crossings) / collisions;
  // Dense gases: neighbour-list renewals (event_driven/neighbour_shells.hpp) instead.
  state.counters["renewals/coll"] =
      static_cast<double>(after.neighbour_rebuilds - before.neighbour_rebuilds) / collisions;
  state.counters["events/coll"] = static_cast<double>(after.events - before.events) / collisions;
}

// Arg: phi x 100.
granjet::Scene gas3d(const benchmark::State& state) {
  return granjet::load_scene(std::string(GRANJET_SCENES_DIR) + "/gas3d.ini",
                             {"gas.phi=" + std::to_string(state.range(0) / 100.0)});
}

void BM_EdGas3d(benchmark::State& state) {
  run<3>(state, granjet::ed::make_ed_simulator<3>(gas3d(state)), 2.0, 0.2);
}

// The shipped scene's whole stretch after the melt, t = 2 to run.t_end, once: the work whose rate
// bench/cli_against_kernel.sh compares with `granjet run` on the same work (BM_EdGas3d times
// whatever stretch after t = 2 its few seconds reach).
void BM_EdGas3dShipped(benchmark::State& state) {
  const granjet::Scene scene = gas3d(state);
  run<3>(state, granjet::ed::make_ed_simulator<3>(scene), 2.0, scene.run.t_end - 2.0);
}

void BM_EdGas3dCells(benchmark::State& state) {
  const granjet::Scene scene = granjet::ed::hard_scene(gas3d(state));
  run<3>(state,
         std::make_unique<granjet::ed::EdSimulator<3>>(
             scene, granjet::build_initial_state<3>(scene), granjet::ed::Verification::kOff,
             granjet::ed::NeighbourSearch::kCells),
         2.0, 0.2);
}

void BM_EdJet2d(benchmark::State& state) {
  const granjet::Scene scene =
      granjet::load_scene(std::string(GRANJET_SCENES_DIR) + "/jet2d.ini", {});
  run<2>(state, granjet::ed::make_ed_simulator<2>(scene), 20.0, 1.0);
}

}  // namespace

BENCHMARK(BM_EdGas3d)->Arg(30)->Arg(45)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EdGas3dShipped)->Arg(30)->Arg(45)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EdGas3dCells)->Arg(45)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EdJet2d)->Unit(benchmark::kMillisecond);
