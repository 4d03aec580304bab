#include "run/run_profile.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

namespace granjet {

nlohmann::json profile_json(const PhaseProfile& profile, double loop_seconds, int threads,
                            const std::vector<std::vector<double>>& by_rank) {
  using Kind = PhaseProfile::Kind;
  nlohmann::json j;
  j["loop_seconds"] = loop_seconds;
  j["threads"] = threads;
  const double scale = loop_seconds > 0.0 ? 1.0 / loop_seconds : 0.0;
  const bool over_ranks = by_rank.size() > 1;
  if (over_ranks) j["ranks"] = by_rank.size();
  nlohmann::json phases = nlohmann::json::array();
  for (std::size_t k = 0; k < profile.phases().size(); ++k) {
    const PhaseProfile::Phase& p = profile.phases()[k];
    if (p.calls == 0) continue;  // a phase this scene never ran (no plate, no tethers ...)
    nlohmann::json phase = {{"name", p.name},
                            {"kind", p.kind == Kind::kSerial ? "serial" : "parallel"},
                            {"seconds", p.seconds},
                            {"calls", p.calls},
                            {"share", p.seconds * scale}};
    if (p.slowest_seconds > 0.0) {
      phase["work_seconds"] = p.work_seconds;
      phase["slowest_seconds"] = p.slowest_seconds;
    }
    if (over_ranks) {
      double fastest = std::numeric_limits<double>::infinity(), slowest = 0.0, sum = 0.0;
      for (const std::vector<double>& row : by_rank) {
        const double s = k < row.size() ? row[k] : 0.0;
        fastest = std::min(fastest, s);
        slowest = std::max(slowest, s);
        sum += s;
      }
      phase["over_ranks"] = {{"fastest", fastest},
                             {"mean", sum / static_cast<double>(by_rank.size())},
                             {"slowest", slowest}};
    }
    phases.push_back(phase);
  }
  j["phases"] = phases;
  const double timed = profile.seconds(Kind::kSerial) + profile.seconds(Kind::kParallel);
  // Step bookkeeping between the phases, and the loop's own scheduling; serial too.
  const double untimed = std::max(0.0, loop_seconds - timed);
  const double serial = profile.seconds(Kind::kSerial) + untimed;
  j["untimed_seconds"] = untimed;
  j["serial_seconds"] = serial;
  j["serial_share"] = serial * scale;
  j["amdahl_limit"] =
      serial > 0.0 ? loop_seconds / serial : std::numeric_limits<double>::infinity();
  return j;
}

std::string profile_text(const nlohmann::json& profile) {
  std::ostringstream out;
  char line[160];
  std::snprintf(line, sizeof line, "profile: %.4g s of loop on %d thread%s\n",
                profile["loop_seconds"].get<double>(), profile["threads"].get<int>(),
                profile["threads"].get<int>() == 1 ? "" : "s");
  out << line;
  std::snprintf(line, sizeof line, "  %-44s %8s %10s %7s %9s %7s %7s\n", "phase", "kind", "seconds",
                "share", "calls", "busy", "uneven");
  out << line;
  const auto percent = [](double part, double whole) {
    char text[16];
    std::snprintf(text, sizeof text, "%.1f%%", whole > 0.0 ? 100.0 * part / whole : 0.0);
    return std::string(text);
  };
  const auto row = [&](const std::string& name, const std::string& kind, double seconds,
                       double share, const std::string& calls, const std::string& busy,
                       const std::string& uneven) {
    std::snprintf(line, sizeof line, "  %-44s %8s %10.4f %6.2f%% %9s %7s %7s\n", name.c_str(),
                  kind.c_str(), seconds, 100.0 * share, calls.c_str(), busy.c_str(),
                  uneven.c_str());
    out << line;
  };
  const double loop = profile["loop_seconds"].get<double>();
  for (const nlohmann::json& p : profile["phases"]) {
    const double seconds = p["seconds"].get<double>();
    const bool shared = p.contains("work_seconds");
    const double work = shared ? p["work_seconds"].get<double>() : 0.0;
    const double slowest = shared ? p["slowest_seconds"].get<double>() : 0.0;
    row(p["name"].get<std::string>(), p["kind"].get<std::string>(), seconds,
        p["share"].get<double>(), std::to_string(p["calls"].get<std::int64_t>()),
        shared ? percent(work, seconds) : "-", shared ? percent(slowest - work, seconds) : "-");
  }
  const double untimed = profile["untimed_seconds"].get<double>();
  row("untimed (bookkeeping between phases)", "serial", untimed, loop > 0.0 ? untimed / loop : 0.0,
      "-", "-", "-");
  std::snprintf(line, sizeof line,
                "  serial share %.2f%% of the loop: no thread count runs it faster than %.3gx\n",
                100.0 * profile["serial_share"].get<double>(),
                profile["amdahl_limit"].get<double>());
  out << line;
  out << "  busy: the threads' mean time on their shares of a phase's loops; uneven: the slowest\n"
         "  share's excess over it; the rest of the phase is forks, joins, barriers and "
         "one-thread\n"
         "  parts\n";
  if (!profile.contains("ranks")) return out.str();
  std::snprintf(line, sizeof line,
                "over %d ranks: each phase's seconds on the fastest rank, the mean, the slowest\n",
                profile["ranks"].get<int>());
  out << line;
  std::snprintf(line, sizeof line, "  %-44s %10s %10s %10s\n", "phase", "fastest", "mean",
                "slowest");
  out << line;
  for (const nlohmann::json& p : profile["phases"]) {
    const nlohmann::json& r = p["over_ranks"];
    std::snprintf(line, sizeof line, "  %-44s %10.4f %10.4f %10.4f\n",
                  p["name"].get<std::string>().c_str(), r["fastest"].get<double>(),
                  r["mean"].get<double>(), r["slowest"].get<double>());
    out << line;
  }
  out << "  the waits for other ranks are in the ranks' phases: there the slowest rank is the\n"
         "  one that waited longest\n";
  return out.str();
}

}  // namespace granjet
