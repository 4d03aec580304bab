// `granjet run` and `granjet resume` as a library: one scene on one backend to its H5MD file,
// with progress rows, a log and a JSON summary. The command and the Python module's
// Simulator.run both come here, so their files are the same.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/scene_support.hpp"
#include "core/simulator.hpp"
#include "core/state_archive.hpp"

namespace granjet {

struct RunOptions {
  std::filesystem::path scene_file;
  std::string backend = "soft_dem";
  std::vector<std::string> overrides;  // "section.key=value"
  std::filesystem::path out;           // empty: <scene file stem>.h5 in the working directory
  std::filesystem::path summary;       // empty: no JSON summary
  bool quiet = false;
  bool log = true;  // <out stem>.log beside the output (run/run_log.hpp)
  // Wall time per phase of the loop and its serial share, reported at the end and in the
  // summary (run/run_profile.hpp).
  bool profile = false;
  // The H5MD author (/h5md/author/name); empty: $GRANJET_AUTHOR, else the login name.
  std::string author;
  // What SIGINT, SIGTERM or SIGHUP leave: a checkpoint at the stop (true), or the last
  // scheduled one (false), from which the resumed run is bit-identical to one never stopped (a
  // checkpoint rebuilds the neighbour list, so an unscheduled one changes the last bits).
  bool checkpoint_on_signal = true;
  // An ensemble: one run per seed (run.seed), each to <out stem>.seed<N>.h5 (and
  // <summary stem>.seed<N>.json); the mean and spread over seeds of the analysis go to `out`
  // and `summary`. Empty: one run with the scene's seed.
  std::vector<std::uint64_t> seeds;
};

// Started by mpirun -n K with K > 1, `command`, which runs as one process for the reason `why`,
// refuses before it reads or writes anything: rank 0 names it (InputError), the other ranks end
// with its exit code in silence (RefusedElsewhere).
void refuse_over_ranks(const std::string& command, const std::string& why);

// Started by mpirun -n K with K > 1, a soft-DEM run or resume spreads over the ranks
// (run/rank_leader.hpp); `command` on the event-driven backend refuses, as above.
void refuse_several_ranks(const std::string& command, const std::string& backend);

// Returns the process exit code: 0 done, 3 blow-up (the output kept as .partial). Throws
// InputError (exit 2) for bad input before any file is written.
int run_command(const RunOptions& options, std::ostream& out);

struct RunOutcome {
  int exit_code = 0;       // as run_command's
  nlohmann::json summary;  // what --summary writes
};

// The run itself, of a simulator made from `support.resolved` (the backend's reading of
// `requested`) and still at t = 0, or restored from `resume_from`: advanced to run.t_end under
// the scene's measurements, frames, progress rows and checkpoints, into `out_file` (written as
// .partial, renamed when complete). options.scene_file and options.overrides only name the run
// in its log; options.seeds is not read.
template <int D>
RunOutcome run_simulation(Simulator<D>& sim, const Scene& requested, const SceneSupport& support,
                          const RunOptions& options, const std::filesystem::path& out_file,
                          std::ostream& out, const StateArchive* resume_from = nullptr);

struct ResumeOptions {
  std::filesystem::path partial;       // RUN.h5.partial with a checkpoint
  std::vector<std::string> overrides;  // only the keys kResumableKeys names
  std::filesystem::path summary;       // empty: no JSON summary
  bool quiet = false;
  bool log = true;                   // appends to the run's log
  bool profile = false;              // as RunOptions::profile
  bool checkpoint_on_signal = true;  // as RunOptions::checkpoint_on_signal
};

// `granjet resume`: the run of a .partial goes on from its last checkpoint, bit-identically to
// a run that was never stopped, to the stored scene's run.t_end (or a later one) and renames
// the file to RUN.h5 when complete.
int resume_command(const ResumeOptions& options, std::ostream& out);

}  // namespace granjet
