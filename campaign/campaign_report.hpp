// What `granjet campaign` prints: the plan (--dry-run: every run, its cost, and the cost of each
// result id) and, at the end, one row per ensemble with how its runs ended.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "campaign/campaign_file.hpp"
#include "campaign/campaign_plan.hpp"

namespace granjet {

// What a run's files, or its exit code, say about it.
enum class RunState { kMissing, kComplete, kBlownUp, kFailed, kInterrupted };
const char* state_name(RunState state);

struct RunOutcome {
  RunState state = RunState::kMissing;
  bool executed = false;  // run by this invocation (else found complete on disk)
  double seconds = 0.0;   // its wall time
};

// Every run with backend, grains, steps and cost; then per result id its groups, runs and cost;
// then the totals with the estimated wall time on `jobs` parallel slots.
void print_dry_run(const CampaignFile& campaign, const CampaignPlan& plan, int jobs,
                   std::ostream& out);

void print_outcome_table(const CampaignPlan& plan, const std::vector<RunOutcome>& outcomes,
                         double wall_seconds, std::ostream& out);

// 3725 s -> "1h02m", 75 s -> "1m15s".
std::string format_duration(double seconds);

}  // namespace granjet
