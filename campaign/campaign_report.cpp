#include "campaign/campaign_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <queue>

#include "run/backend_factory.hpp"

namespace granjet {
namespace {

std::string printf_string(const char* format, auto... values) {
  char line[256];
  std::snprintf(line, sizeof line, format, values...);
  return line;
}

// Sums of run costs.
struct CostSum {
  std::size_t runs = 0;
  double particle_steps = 0.0, grain_time = 0.0, seconds = 0.0;
  void add(const RunCost& c) {
    ++runs;
    particle_steps += c.particle_steps;
    grain_time += c.grain_time;
    seconds += c.seconds;
  }
};

std::string cost_columns(const CostSum& c) {
  return printf_string("%6zu %16.3g %12.3g %11.2f", c.runs, c.particle_steps, c.grain_time,
                       c.seconds / 3600.0);
}

// The wall time of running `plan` on `slots` parallel slots, longest run first onto the slot
// that frees first (as the runner hands them out).
double makespan(const CampaignPlan& plan, int slots) {
  std::vector<double> costs;
  for (const PlannedRun& r : plan.runs) costs.push_back(r.cost.seconds);
  std::sort(costs.begin(), costs.end(), std::greater<>());
  std::priority_queue<double, std::vector<double>, std::greater<>> free_at;
  for (int s = 0; s < std::max(1, slots); ++s) free_at.push(0.0);
  double end = 0.0;
  for (double c : costs) {
    const double t = free_at.top() + c;
    free_at.pop();
    free_at.push(t);
    end = std::max(end, t);
  }
  return end;
}

}  // namespace

const char* state_name(RunState state) {
  switch (state) {
    case RunState::kMissing:
      return "missing";
    case RunState::kComplete:
      return "complete";
    case RunState::kBlownUp:
      return "blown_up";
    case RunState::kFailed:
      return "failed";
    case RunState::kInterrupted:
      return "interrupted";
  }
  return "?";
}

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s >= 3600) return printf_string("%ldh%02ldm", s / 3600, s / 60 % 60);
  if (s >= 60) return printf_string("%ldm%02lds", s / 60, s % 60);
  return printf_string("%lds", s);
}

void print_dry_run(const CampaignFile& campaign, const CampaignPlan& plan, int jobs,
                   std::ostream& out) {
  out << printf_string("%-58s %-13s %7s %9s %15s %8s\n", "run", "backend", "grains", "steps",
                       "particle-steps", "est. s");
  for (const PlannedRun& r : plan.runs)
    out << printf_string("%-58s %-13s %7lld %9lld %15.4g %8.1f\n", r.name.c_str(),
                         r.backend.c_str(), static_cast<long long>(r.cost.grains),
                         static_cast<long long>(r.cost.steps), r.cost.particle_steps,
                         r.cost.seconds);

  // Result ids in the order the file first names them, with the groups serving them.
  std::vector<std::string> ids;
  for (const CampaignGroup& g : campaign.groups)
    for (const std::string& id : g.results)
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  out << "\n"
      << printf_string("%-12s %-48s %6s %16s %12s %11s\n", "result", "groups", "runs",
                       "particle-steps", "grain-time", "CPU hours");
  CostSum total;
  for (const PlannedRun& r : plan.runs) total.add(r.cost);
  for (const std::string& id : ids) {
    CostSum sum;
    std::string groups;
    for (std::size_t g = 0; g < campaign.groups.size(); ++g) {
      const CampaignGroup& group = campaign.groups[g];
      if (std::find(group.results.begin(), group.results.end(), id) == group.results.end())
        continue;
      bool planned = false;
      for (const PlannedRun& r : plan.runs)
        if (r.group == g) {
          sum.add(r.cost);
          planned = true;
        }
      if (planned) groups += (groups.empty() ? "" : ",") + group.name;
    }
    if (sum.runs > 0)
      out << printf_string("%-12s %-48s ", id.c_str(), groups.c_str()) << cost_columns(sum) << "\n";
  }
  out << printf_string("%-12s %-48s ", "total", "") << cost_columns(total) << "\n\n"
      << "campaign " << campaign.name << " (" << campaign.file.string() << "): " << plan.runs.size()
      << " runs in " << plan.ensembles.size() << " ensembles; about "
      << format_duration(total.seconds) << " of CPU time, " << format_duration(makespan(plan, jobs))
      << " of wall time on " << jobs << " parallel slot(s)\n"
      << "(estimates per core from";
  for (const std::string& name : backend_names()) {
    const Backend& b = backend_named(name);
    out << printf_string(" %.2g (2D) and %.2g (3D) %s (%s)", b.rate_2d, b.rate_3d,
                         b.counts_events ? "grain time units/s" : "particle-steps/s", name.c_str())
        << (name == backend_names().back() ? ")\n" : ";");
  }
}

void print_outcome_table(const CampaignPlan& plan, const std::vector<RunOutcome>& outcomes,
                         double wall_seconds, std::ostream& out) {
  // "to do": interrupted, or never started (an interrupted invocation); the next one runs them.
  out << "\n"
      << printf_string("%-50s %8s %8s %8s %7s %7s %10s\n", "ensemble", "complete", "blown_up",
                       "failed", "to do", "reused", "run s");
  std::size_t complete = 0, blown_up = 0, failed = 0, to_do = 0, reused = 0, executed = 0;
  double run_seconds = 0.0;
  for (const PlannedEnsemble& e : plan.ensembles) {
    std::size_t c = 0, b = 0, f = 0, t = 0, u = 0;
    double s = 0.0;
    for (std::size_t r : e.runs) {
      const RunOutcome& o = outcomes[r];
      c += o.state == RunState::kComplete;
      b += o.state == RunState::kBlownUp;
      f += o.state == RunState::kFailed;
      t += o.state == RunState::kInterrupted || o.state == RunState::kMissing;
      u += !o.executed && o.state != RunState::kMissing;
      executed += o.executed;
      s += o.seconds;
    }
    out << printf_string("%-50s %4zu/%-3zu %8zu %8zu %7zu %7zu %10.1f\n", e.name.c_str(), c,
                         e.runs.size(), b, f, t, u, s);
    complete += c;
    blown_up += b;
    failed += f;
    to_do += t;
    reused += u;
    run_seconds += s;
  }
  out << printf_string("%-50s %4zu/%-3zu %8zu %8zu %7zu %7zu %10.1f\n", "total", complete,
                       plan.runs.size(), blown_up, failed, to_do, reused, run_seconds)
      << "wall time " << format_duration(wall_seconds) << " for " << executed << " runs executed ("
      << reused << " found done and reused)\n";
}

}  // namespace granjet
