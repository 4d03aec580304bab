// The most a machine gives N threads that share nothing: each thread runs its own dependent
// arithmetic chain (the cores' clock alone), or reads its own array again and again, one that
// fits its core's second-level cache and one that only memory holds. Under a hypervisor or with
// all cores clocked down, these fall short of N times one thread, and no threaded code beats
// them; docs/performance.md sets the soft DEM's thread scaling beside them. Counts beyond the
// CPUs this process may use are skipped.
//   build/bench/granjet_bench --benchmark_filter='BM_Threads'
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <thread>
#include <vector>

namespace {

bool fits(benchmark::State& state) {
  if (state.threads() <= static_cast<int>(std::thread::hardware_concurrency())) return true;
  state.SkipWithError("more threads than CPUs");
  return false;
}

void BM_ThreadsArithmetic(benchmark::State& state) {
  if (!fits(state)) return;
  constexpr std::int64_t kChain = 1 << 16;  // dependent multiply-adds per iteration
  double x = 1.0 + 1e-9 * state.thread_index();
  for (auto _ : state) {
    for (std::int64_t k = 0; k < kChain; ++k) x = x * 0.999999 + 1e-7;
    benchmark::DoNotOptimize(x);
  }
  state.SetItemsProcessed(state.iterations() * kChain);  // summed over the threads
}

// Each thread sums its own array of state.range(0) KiB; integers, whose sum the compiler may
// reorder into vector lanes, so that the loop waits on the cache or memory, not on the adds.
void BM_ThreadsRead(benchmark::State& state) {
  if (!fits(state)) return;
  const auto count = static_cast<std::size_t>(state.range(0)) * 1024 / sizeof(std::uint64_t);
  const std::vector<std::uint64_t> data(count, 1);  // written by the thread that reads it
  for (auto _ : state) {
    std::uint64_t sum = 0;
    for (std::uint64_t value : data) sum += value;
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(state.iterations() *
                          static_cast<std::int64_t>(count * sizeof(std::uint64_t)));
}

}  // namespace

BENCHMARK(BM_ThreadsArithmetic)->ThreadRange(1, 64)->UseRealTime();
BENCHMARK(BM_ThreadsRead)->Arg(512)->Arg(65536)->ThreadRange(1, 64)->UseRealTime();
