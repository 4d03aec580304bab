// Runs a planned campaign: each run as `granjet run` in a process of its own, N at a time on this
// machine and one at a time on every other MPI rank, handed out by rank 0 as slots become free;
// runs whose complete output is already there are skipped; each ensemble is merged as soon as
// all its seeds are in. Rank 0 keeps DIR/manifest.json and prints progress.
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <vector>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_plan.hpp"
#include "campaign/campaign_report.hpp"
#include "campaign/child_process.hpp"
#include "campaign/mpi_world.hpp"

namespace granjet {

// kComplete: the output under its final name, a summary with status complete, and the stored
// scene and backend hash to run.hash. kBlownUp: the summary reports a blow-up and the kept
// .partial holds the same scene (a blow-up is deterministic: rerunning repeats it). Else
// kMissing.
RunState stored_state(const PlannedRun& run);

// Why the next invocation would run `run`, for --dry-run; empty when it is done (kComplete or
// kBlownUp). "resumes from its checkpoint at t = T"; "its file holds another scene: KEY A -> B,
// ..." (the keys whose resolved values differ, the stored scene read by today's parser, so an
// upgrade that changes a default names it); "stopped before its end (status S)"; "not run yet".
std::string why_it_runs(const PlannedRun& run);

// Writes the run's resolved scene (.ini), clears its earlier outputs and starts
// `granjet run NAME.ini --backend B --out NAME.h5 --summary NAME.json` with its log in NAME.log.
ChildProcess start_run(const PlannedRun& run);

struct RunnerOptions {
  std::filesystem::path out_dir;  // DIR: the manifest's place
  int jobs = 1;                   // local slots on rank 0
  bool quiet = false;
  nlohmann::json invocation;  // what the manifest records of this invocation
};

// Rank 0. Returns the exit code: 0 every run complete, 3 some blew up, 1 some failed.
int coordinate_campaign(const CampaignFile& campaign, const CampaignPlan& plan, MpiWorld& world,
                        const RunnerOptions& options, std::ostream& out);
// Every other rank: runs what rank 0 assigns until it says stop.
void work_for_campaign(const CampaignPlan& plan, MpiWorld& world);

}  // namespace granjet
