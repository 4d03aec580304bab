// What a team of N OpenMP threads pays to synchronise, with no work between: one barrier, and
// one parallel region's fork and join. A soft-DEM step at many threads crosses a handful of
// each, so where a step's shared work falls to tens of microseconds these set its floor
// (docs/performance.md). Counts beyond the CPUs this process may use are skipped: an
// oversubscribed barrier measures the scheduler instead.
//   build/bench/granjet_bench --benchmark_filter='BM_Omp'
#include <benchmark/benchmark.h>
#include <omp.h>

#include <chrono>
#include <cstdint>

namespace {

bool fits(benchmark::State& state, int team) {
  if (team <= omp_get_num_procs()) return true;
  state.SkipWithError("more threads than CPUs");
  return false;
}

void report(benchmark::State& state, std::chrono::steady_clock::time_point start, std::int64_t per,
            const char* counter) {
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  state.counters[counter] = elapsed.count() / static_cast<double>(state.iterations() * per);
}

void BM_OmpBarrier(benchmark::State& state) {
  const auto team = static_cast<int>(state.range(0));
  if (!fits(state, team)) return;
  constexpr std::int64_t kBarriers = 10000;  // per iteration
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
#pragma omp parallel num_threads(team)
    for (std::int64_t b = 0; b < kBarriers; ++b) {
#pragma omp barrier
    }
  }
  report(state, start, kBarriers, "ns_per_barrier");
}

void BM_OmpForkJoin(benchmark::State& state) {
  const auto team = static_cast<int>(state.range(0));
  if (!fits(state, team)) return;
  constexpr std::int64_t kRegions = 2000;  // per iteration
  std::int64_t sink = 0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    for (std::int64_t r = 0; r < kRegions; ++r) {
#pragma omp parallel num_threads(team)
      if (omp_get_thread_num() == 0) ++sink;  // one store, so the region is not empty
    }
  }
  benchmark::DoNotOptimize(sink);
  report(state, start, kRegions, "ns_per_region");
}

}  // namespace

BENCHMARK(BM_OmpBarrier)->RangeMultiplier(2)->Range(2, 64)->UseRealTime();
BENCHMARK(BM_OmpForkJoin)->RangeMultiplier(2)->Range(2, 64)->UseRealTime();
