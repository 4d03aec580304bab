// Cell grid + Verlet half-list build on the initial 3D jet (20,000 grains, fcc), with one radius
// for all grains as the soft DEM builds a monodisperse scene's list (kUniform) and with a radius
// read per candidate.
#include <benchmark/benchmark.h>

#include "core/initial_state.hpp"
#include "core/neighbour_list.hpp"

namespace {

template <bool kUniform>
void BM_NeighbourBuildJet3d(benchmark::State& state) {
  const granjet::Scene scene;  // the defaults are jet3d's
  const granjet::Particles<3> p = granjet::build_initial_state<3>(scene);
  const double skin = 0.01 * static_cast<double>(state.range(0));
  granjet::CellGrid<3> grid;
  granjet::PairList pairs;
  std::vector<granjet::Vec<3>> sorted;
  std::vector<double> radius;
  for (auto _ : state) {
    grid.build(p.position(), 1.0 + skin);
    sorted.clear();
    radius.clear();
    for (std::uint32_t k : grid.order()) {
      sorted.push_back(p.position()[k]);
      radius.push_back(p.radius()[k]);
    }
    granjet::build_half_pairs<3, kUniform>(
        grid, sorted, radius, skin, [](auto, auto) { return false; }, pairs);
    benchmark::DoNotOptimize(pairs.partner.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(p.size()));
  state.counters["pairs"] = static_cast<double>(pairs.size());
}

}  // namespace

BENCHMARK_TEMPLATE(BM_NeighbourBuildJet3d, true)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_NeighbourBuildJet3d, false)->Arg(30)->Arg(40)->Unit(benchmark::kMillisecond);
