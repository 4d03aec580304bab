// The ranks a campaign runs on. Built with Open MPI (GRANJET_HAS_MPI) and started by mpirun, it
// is MPI_COMM_WORLD: rank 0 coordinates (hands out runs one at a time as ranks become free, so
// the assignment is dynamic) and every rank runs what it is given. Otherwise it is a world of one
// rank, and a build without MPI started by mpirun with several ranks refuses to run (each rank
// would run the whole campaign into the same directory).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/rank_team.hpp"  // launched_ranks

namespace granjet {

class MpiWorld {
 public:
  MpiWorld();
  ~MpiWorld();  // waits for every rank without spinning, then MPI_Finalize; aborts all ranks
                // when it is left by an exception, so none waits forever for a lost coordinator
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Every rank's host name, by rank (collective: every rank calls it once, in the same order).
  std::vector<std::string> hostnames();

  // A worker's report: the run it finished (-1 for none yet), its exit code and wall seconds.
  struct Report {
    std::int64_t run = -1;
    int exit_code = 0;
    double seconds = 0.0;
    int rank = 0;  // the sender
  };
  // Rank 0: a report waiting from any rank, without blocking.
  std::optional<Report> try_receive();
  // Rank 0: the run `rank` is to do next; -1 tells it to stop.
  void assign(int rank, std::int64_t run);
  // Other ranks: report to rank 0, then wait (without spinning) for the next run, -1 to stop.
  std::int64_t report_and_receive(const Report& report);

 private:
  int rank_ = 0;
  int size_ = 1;
  bool initialised_ = false;
};

// Whether this build can spread a campaign over MPI ranks.
bool built_with_mpi();

}  // namespace granjet
