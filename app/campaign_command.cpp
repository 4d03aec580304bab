#include "app/campaign_command.hpp"

#include <optional>
#include <ostream>

#include "analysis/file_lock.hpp"
#include "campaign/campaign_file.hpp"
#include "campaign/campaign_plan.hpp"
#include "campaign/campaign_report.hpp"
#include "campaign/campaign_runner.hpp"
#include "campaign/campaign_status.hpp"
#include "campaign/child_process.hpp"
#include "campaign/mpi_world.hpp"
#include "core/errors.hpp"
#include "run/version.hpp"

namespace granjet {

int campaign_command(const CampaignOptions& options, std::ostream& out) {
  if (options.jobs < 0 || options.jobs > 1024)
    throw InputError("--jobs", std::to_string(options.jobs) + " is not in 1..1024");
  MpiWorld world;
  const CampaignFile campaign = load_campaign(options.file);
  PlanOptions plan_options;
  // --quick runs replace a full run's files of the same name, so they default elsewhere.
  const std::string stem = options.file.stem().string() + (options.quick ? "-quick" : "");
  plan_options.out_dir =
      options.out_dir.empty() ? std::filesystem::path("out") / stem : options.out_dir;
  plan_options.quick = options.quick;
  plan_options.only = options.only;
  if (options.status) {
    if (world.rank() == 0) print_campaign_status(plan_options.out_dir, out);
    return 0;
  }
  const CampaignPlan plan = plan_campaign(campaign, plan_options);
  const int jobs = options.jobs > 0 ? options.jobs : world.size() > 1 ? 1 : available_cores();

  if (options.dry_run) {
    if (world.rank() == 0) {
      print_dry_run(campaign, plan, jobs + world.size() - 1, out);
      print_what_would_run(plan, plan_options.out_dir, out);
    }
    return 0;
  }
  if (world.rank() != 0) {
    work_for_campaign(plan, world);
    return 0;
  }
  std::filesystem::create_directories(plan_options.out_dir);
  // One campaign per DIR: two would run the same runs into the same files.
  std::optional<analysis::FileLock> lock;
  try {
    lock.emplace(campaign_lock(plan_options.out_dir));
  } catch (const analysis::FileBusyError&) {
    throw InputError("--out", "'" + plan_options.out_dir.string() +
                                  "' is being run by another granjet campaign; wait for it "
                                  "(--status shows where it stands) or name another --out");
  }
  RunnerOptions runner;
  runner.out_dir = plan_options.out_dir;
  runner.jobs = jobs;
  runner.quiet = options.quiet;
  runner.invocation = {{"version", kVersion},
                       {"commit", kCommit},
                       {"command", options.command_line},
                       {"quick", options.quick},
                       {"only", options.only}};
  return coordinate_campaign(campaign, plan, world, runner, out);
}

}  // namespace granjet
