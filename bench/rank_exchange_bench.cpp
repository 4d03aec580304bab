// The ghost states the ranks swap at every step, as a lone exchange between MPI ranks:
// RankTeam::exchange_into (core/rank_team.cpp: a message up to 16 KiB goes as pieces that each
// go eagerly) against one MPI message each way, at lengths around jet3d's 15 kB a step. Every
// rank exchanges with every other, so each iteration waits for all of them, as a step does.
// The second argument is how late one rank comes, in microseconds (the ranks take turns): in a
// run the ranks never finish their passes together, and an iteration then lasts that long plus
// what the exchange costs the late rank.
//
//   mpirun -n 2 --bind-to core build/bench/granjet_rank_exchange_bench
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

void BM_RankTeamExchange(benchmark::State& state) {
  Lists lists(static_cast<std::size_t>(state.range(0)));
  MPI_Barrier(MPI_COMM_WORLD);
  int iteration = 0;
  for (auto _ : state) {
    come_late(iteration++, lists.world, state.range(1));
    lists.world.exchange_into(lists.to, lists.from, lists.others, true);
  }
  state.SetBytesProcessed(state.iterations() * state.range(0) * std::ssize(lists.others));
}

void BM_OneMessageEachWay(benchmark::State& state) {
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

BENCHMARK(BM_RankTeamExchange)
    ->ArgsProduct({{2048, 8192, 15000, 32768, 65536, 131072}, {0, 20}})
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
