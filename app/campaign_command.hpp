// `granjet campaign FILE`: every run of a campaign file (campaign_file.hpp), N at a time on this
// machine or spread over MPI ranks, resumable, each group's seeds merged into ensembles.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace granjet {

struct CampaignOptions {
  std::filesystem::path file;
  std::filesystem::path out_dir;  // empty: out/<file stem>, out/<file stem>-quick with --quick
  int jobs = 0;                   // 0: the cores this process may use (1 per rank under MPI)
  bool quick = false;
  bool dry_run = false;
  bool status = false;  // print where DIR stands (campaign_status.hpp), run nothing
  bool quiet = false;
  std::vector<std::string> only;          // result ids
  std::vector<std::string> command_line;  // recorded in the manifest
};

// Returns the exit code: 0 every run complete, 3 some blew up, 1 some failed, 128 + the signal
// when interrupted. Throws InputError (exit 2) for a bad campaign file or option, or a DIR
// another campaign is running in, before anything is run or written.
int campaign_command(const CampaignOptions& options, std::ostream& out);

}  // namespace granjet
