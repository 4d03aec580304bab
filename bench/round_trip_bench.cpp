// How long a cache line takes to go from one core to another and back: two threads, pinned to
// the first two CPUs this process may use, hand a counter to and fro. Thread scaling depends on
// it (a thread reads the grains another one wrote a phase earlier), and under a hypervisor it
// can change from minute to minute (two AMD EPYC vCPUs: 80-130 ns at times, 390-450 ns at
// others), so a two-thread figure means little without it. Run it before and after:
//   build/bench/granjet_bench --benchmark_filter=BM_CacheLineRoundTrip
#include <benchmark/benchmark.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

namespace {

// The first two CPUs of this process's affinity mask (none: fewer than two).
std::vector<int> first_two_cpus() {
  cpu_set_t allowed;
  std::vector<int> cpus;
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return cpus;
  for (int c = 0; c < CPU_SETSIZE && cpus.size() < 2; ++c)
    if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
  return cpus;
}

void pin_to(int cpu) {
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  pthread_setaffinity_np(pthread_self(), sizeof one, &one);
}

void BM_CacheLineRoundTrip(benchmark::State& state) {
  const std::vector<int> cpus = first_two_cpus();
  if (cpus.size() < 2) {
    state.SkipWithError("needs two CPUs");
    return;
  }
  constexpr std::int64_t kTrips = 100000;  // per iteration
  alignas(64) std::atomic<std::int64_t> ball{0};
  std::atomic<bool> done{false};
  // The partner answers every odd value with the next even one, until told to stop.
  std::thread partner([&] {
    pin_to(cpus[1]);
    std::int64_t seen = 0;
    while (!done.load(std::memory_order_relaxed)) {
      const std::int64_t v = ball.load(std::memory_order_acquire);
      if (v != seen && (v & 1) != 0) {
        seen = v;
        ball.store(v + 1, std::memory_order_release);
      }
    }
  });
  cpu_set_t before;
  pthread_getaffinity_np(pthread_self(), sizeof before, &before);
  pin_to(cpus[0]);
  std::int64_t value = 0;
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    for (std::int64_t trip = 0; trip < kTrips; ++trip) {
      ball.store(++value, std::memory_order_release);
      while (ball.load(std::memory_order_acquire) != value + 1) {
      }
      ++value;
    }
  }
  const std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
  done.store(true, std::memory_order_relaxed);
  partner.join();
  pthread_setaffinity_np(pthread_self(), sizeof before, &before);  // the next benchmarks' CPUs
  state.counters["ns_per_round_trip"] =
      elapsed.count() / static_cast<double>(state.iterations() * kTrips);
}

}  // namespace

BENCHMARK(BM_CacheLineRoundTrip)->UseRealTime()->Unit(benchmark::kMillisecond);
