// The ghost states the ranks swap at every step, as a lone exchange between MPI ranks:
// RankTeam::exchange_into (core/rank_team.cpp: a message up to 16 KiB goes as pieces that each
// go eagerly) against one MPI message each way, at lengths around jet3d's 15 kB a step. Every
// rank exchanges with every other, so each iteration waits for all of them, as a step does.
// The second argument is how late one rank comes, in microseconds (the ranks take turns): in a
// run the ranks never finish their passes together, and an iteration then lasts that long plus
// what the exchange costs the late rank. The third says whether the receivers know the lengths
// (1) or take what comes (0, matched by MPI_Mprobe as the ghost states of a step are).
//
//   mpirun -n 2 --bind-to core build/bench/granjet_rank_exchange_bench
//   mpirun -n 1 build/bench/granjet_rank_exchange_bench --benchmark_filter=LockStep  (reference)
//
// BM_LockStep is the ceiling of any decomposition that meets at every step: each rank does the
// same work and then joins a one-word all-reduce, as a step's agreement. On quiet cores the ranks
// arrive together and `busy` (each rank's share of the wall time spent on its work, the mean
// over ranks) stays near 1; a host whose cores stall now and then makes every rank wait for the
// one that stalled. K ranks then run at most K x busy x (step_us with `mpirun -n 1` over
// step_us with K) times as fast as one: the last factor is what the ranks cost each other in
// shared caches and memory.
//
// Each benchmark runs a fixed number of iterations, the same on every rank (Google Benchmark
// would otherwise choose a count per rank, and the ranks would wait for one another for ever);
// rank 0 reports.
#include <benchmark/benchmark.h>
#include <mpi.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/rank_team.hpp"

namespace granjet {
namespace {

constexpr int kIterations = 20000;

struct Lists {
  explicit Lists(std::size_t bytes) : to(world.size()), from(world.size()) {
    for (int r = 0; r < world.size(); ++r) {
      if (r == world.rank()) continue;
      others.push_back(r);
      to[r].assign(bytes, static_cast<std::uint8_t>(world.rank()));
      from[r].assign(bytes, 0);
    }
  }
  RankTeam world = RankTeam::world();
  std::vector<int> others;
  std::vector<std::vector<std::uint8_t>> to, from;
};

// Rank `iteration` mod K works for `micros` before its exchange; the others go straight to it.
void come_late(int iteration, const RankTeam& world, std::int64_t micros) {
  if (micros == 0 || iteration % world.size() != world.rank()) return;
  const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(micros);
  while (std::chrono::steady_clock::now() < until) {
  }
}

bool has_partners(benchmark::State& state) {
  if (!RankTeam::world().alone()) return true;
  state.SkipWithError("an exchange needs 2 ranks or more");
  return false;
}

void BM_RankTeamExchange(benchmark::State& state) {
  if (!has_partners(state)) return;
  Lists lists(static_cast<std::size_t>(state.range(0)));
  MPI_Barrier(MPI_COMM_WORLD);
  int iteration = 0;
  for (auto _ : state) {
    come_late(iteration++, lists.world, state.range(1));
    lists.world.exchange_into(lists.to, lists.from, lists.others, state.range(2) != 0);
  }
  state.SetBytesProcessed(state.iterations() * state.range(0) * std::ssize(lists.others));
}

void BM_OneMessageEachWay(benchmark::State& state) {
  if (!has_partners(state)) return;
  Lists lists(static_cast<std::size_t>(state.range(0)));
  const int count = static_cast<int>(state.range(0));
  std::vector<MPI_Request> requests(2 * lists.others.size());
  MPI_Barrier(MPI_COMM_WORLD);
  int iteration = 0;
  for (auto _ : state) {
    come_late(iteration++, lists.world, state.range(1));
    MPI_Request* request = requests.data();
    for (int r : lists.others) {
      MPI_Irecv(lists.from[r].data(), count, MPI_BYTE, r, 12, MPI_COMM_WORLD, request++);
      MPI_Isend(lists.to[r].data(), count, MPI_BYTE, r, 12, MPI_COMM_WORLD, request++);
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  }
  state.SetBytesProcessed(state.iterations() * state.range(0) * std::ssize(lists.others));
}

// Each rank's work per step: a dependent chain of `chain` multiply-adds, then a sum over its own
// array of `kib` KiB (0: none), which at a few MiB lives in the cache the cores share.
void BM_LockStep(benchmark::State& state) {
  const RankTeam world = RankTeam::world();
  const std::int64_t chain = state.range(0);
  const std::vector<std::uint64_t> data(static_cast<std::size_t>(state.range(1)) * 128, 1);
  double x = 1.0, busy = 0.0;
  std::vector<double> agreed(1);
  world.any(true);  // the ranks start together (alone, too: `mpirun -n 1` is the reference)
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    const auto begin = std::chrono::steady_clock::now();
    for (std::int64_t k = 0; k < chain; ++k) x = x * 0.999999 + 1e-7;
    std::uint64_t sum = 0;
    for (std::uint64_t value : data) sum += value;
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(sum);
    busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    agreed[0] = x;
    world.max(agreed);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double shares = 0.0;
  for (double share : world.all_gather<double>(std::vector<double>{busy / wall})) shares += share;
  state.counters["busy"] = shares / world.size();
  state.counters["step_us"] = 1e6 * busy / static_cast<double>(state.iterations());
}

BENCHMARK(BM_LockStep)
    ->Args({1 << 14, 0})
    ->Args({1 << 16, 0})
    ->Args({1 << 18, 0})
    ->Args({0, 4096})
    ->Args({0, 16384})
    ->Iterations(kIterations / 4);
BENCHMARK(BM_RankTeamExchange)
    ->ArgsProduct({{2048, 8192, 15000, 32768, 65536, 131072}, {0, 20}, {1, 0}})
    ->Iterations(kIterations);
BENCHMARK(BM_OneMessageEachWay)
    ->ArgsProduct({{2048, 8192, 15000, 32768, 65536, 131072}, {0, 20}})
    ->Iterations(kIterations);

}  // namespace
}  // namespace granjet

int main(int argc, char** argv) {
  granjet::MpiSession mpi;
  benchmark::Initialize(&argc, argv);
  if (granjet::RankTeam::world().rank() == 0) {
    benchmark::RunSpecifiedBenchmarks();
  } else {
    struct Silent : benchmark::BenchmarkReporter {
      bool ReportContext(const Context&) override { return true; }
      void ReportRuns(const std::vector<Run>&) override {}
    } silent;
    benchmark::RunSpecifiedBenchmarks(&silent);
  }
  benchmark::Shutdown();
}
