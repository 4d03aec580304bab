// `granjet run`: one scene on one backend, with progress rows, H5MD output and a JSON summary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace granjet {

struct RunOptions {
  std::filesystem::path scene_file;
  std::string backend = "soft_dem";
  std::vector<std::string> overrides;  // "section.key=value"
  std::filesystem::path out;           // empty: <scene file stem>.h5 in the working directory
  std::filesystem::path summary;       // empty: no JSON summary
  bool quiet = false;
  bool log = true;  // <out stem>.log beside the output (app/run_log.hpp)
  // Wall time per phase of the loop and its serial share, reported at the end and in the
  // summary (run/run_profile.hpp).
  bool profile = false;
  // The H5MD author (/h5md/author/name); empty: $GRANJET_AUTHOR, else the login name.
  std::string author;
  // An ensemble: one run per seed (run.seed), each to <out stem>.seed<N>.h5 (and
  // <summary stem>.seed<N>.json); the mean and spread over seeds of the analysis go to `out`
  // and `summary`. Empty: one run with the scene's seed.
  std::vector<std::uint64_t> seeds;
};

// Returns the process exit code: 0 done, 3 blow-up (the output kept as .partial). Throws
// InputError (exit 2) for bad input before any file is written.
int run_command(const RunOptions& options, std::ostream& out);

struct ResumeOptions {
  std::filesystem::path partial;       // RUN.h5.partial with a checkpoint
  std::vector<std::string> overrides;  // only the keys kResumableKeys names
  std::filesystem::path summary;       // empty: no JSON summary
  bool quiet = false;
  bool log = true;       // appends to the run's log
  bool profile = false;  // as RunOptions::profile
};

// `granjet resume`: the run of a .partial goes on from its last checkpoint, bit-identically to
// a run that was never stopped, to the stored scene's run.t_end (or a later one) and renames
// the file to RUN.h5 when complete.
int resume_command(const ResumeOptions& options, std::ostream& out);

}  // namespace granjet
