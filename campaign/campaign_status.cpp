#include "campaign/campaign_status.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "analysis/file_lock.hpp"
#include "campaign/campaign_report.hpp"
#include "campaign/campaign_runner.hpp"
#include "core/errors.hpp"

namespace granjet {

std::filesystem::path campaign_lock(const std::filesystem::path& dir) {
  return dir / "campaign.lock";
}

void print_campaign_status(const std::filesystem::path& dir, std::ostream& out) {
  std::ifstream in(dir / "manifest.json");
  if (!in) throw InputError(dir.string(), "holds no manifest.json: no campaign ran there");
  nlohmann::json m;
  try {
    m = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError((dir / "manifest.json").string(), std::string("is not JSON: ") + e.what());
  }
  const bool running = analysis::FileLock::held(campaign_lock(dir));
  const nlohmann::json& last = m["invocations"].back();
  out << "campaign " << m.value("campaign", std::string("?")) << " in " << dir.string() << ": "
      << (running ? "running" : "not running") << " (last started " << last.value("started", "?")
      << " on " << last.value("host", "?") << ", " << last.value("jobs", 1) << " job(s))\n";

  std::map<std::string, std::size_t> by_status;
  double to_run = 0.0;
  std::size_t runs = 0;
  for (const auto& [name, run] : m["runs"].items()) {
    std::string status = run.value("status", std::string("pending"));
    // Left "running" by a campaign that ended without a word (kill -9, a lost MPI rank).
    if (status == "running" && !running) status = "stopped";
    ++by_status[status];
    ++runs;
    if (status != "complete" && status != "blown_up")
      to_run += run["cost"].value("estimated_seconds", 0.0);
  }
  out << "runs: " << runs;
  for (const auto& [status, count] : by_status) out << ", " << count << " " << status;
  const int slots = std::max(1, last.value("jobs", 1) + last.value("ranks", 1) - 1);
  out << "\nstill to run: about " << format_duration(to_run / slots) << " on " << slots
      << " slot(s) (the plan's estimates)\n";
  for (const auto& [name, run] : m["runs"].items()) {
    const std::string status = run.value("status", std::string());
    if (status == "failed" || status == "interrupted" || status == "blown_up")
      out << "  " << name << ": " << status << " (exit code " << run.value("exit_code", -1)
          << ", log " << run.value("log", std::string("?")) << ")\n";
  }
}

void print_what_would_run(const CampaignPlan& plan, const std::filesystem::path& dir,
                          std::ostream& out) {
  std::map<std::string, std::size_t> by_reason;
  std::vector<std::string> changed;
  std::size_t done = 0;
  for (const PlannedRun& run : plan.runs) {
    const std::string why = why_it_runs(run);
    if (why.empty()) {
      ++done;
      continue;
    }
    // Counted by the reason's kind, the part before its details.
    ++by_reason[why.substr(0, std::min(why.find(':'), why.find(" at t = ")))];
    if (why.rfind("its file holds another scene", 0) == 0) changed.push_back(run.name + ": " + why);
  }
  out << "in " << dir.string() << ": " << done << " of " << plan.runs.size()
      << " runs done; the next invocation runs " << plan.runs.size() - done;
  for (const auto& [reason, count] : by_reason) out << "; " << count << " " << reason;
  out << "\n";
  for (const std::string& line : changed) out << "  " << line << "\n";
}

}  // namespace granjet
