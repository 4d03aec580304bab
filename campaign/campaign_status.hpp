// `granjet campaign FILE --status`: where a campaign's directory stands, read from its
// manifest alone (nothing is locked, written or run): whether a campaign runs there now, the
// runs by status, the estimated time still to run, and the failures with their logs.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "campaign/campaign_plan.hpp"

namespace granjet {

// DIR/campaign.lock: held by the one `granjet campaign` that runs in DIR.
std::filesystem::path campaign_lock(const std::filesystem::path& dir);

// Throws InputError naming DIR when it holds no manifest.
void print_campaign_status(const std::filesystem::path& dir, std::ostream& out);

// For --dry-run: what the next invocation in DIR would run and why, counted by reason
// (why_it_runs), with every run whose file holds another scene and the keys that changed: what
// an upgrade or an edited campaign file would redo.
void print_what_would_run(const CampaignPlan& plan, const std::filesystem::path& dir,
                          std::ostream& out);

}  // namespace granjet
