#include "run/run_profile.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

namespace granjet {

nlohmann::json profile_json(const PhaseProfile& profile, double loop_seconds, int threads) {
  using Kind = PhaseProfile::Kind;
  nlohmann::json j;
  j["loop_seconds"] = loop_seconds;
  j["threads"] = threads;
  const double scale = loop_seconds > 0.0 ? 1.0 / loop_seconds : 0.0;
  nlohmann::json phases = nlohmann::json::array();
  for (const PhaseProfile::Phase& p : profile.phases()) {
    if (p.calls == 0) continue;  // a phase this scene never ran (no plate, no tethers ...)
    phases.push_back({{"name", p.name},
                      {"kind", p.kind == Kind::kSerial ? "serial" : "parallel"},
                      {"seconds", p.seconds},
                      {"calls", p.calls},
                      {"share", p.seconds * scale}});
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
  std::snprintf(line, sizeof line, "  %-42s %8s %10s %7s %9s\n", "phase", "kind", "seconds",
                "share", "calls");
  out << line;
  const auto row = [&](const std::string& name, const std::string& kind, double seconds,
                       double share, const std::string& calls) {
    std::snprintf(line, sizeof line, "  %-42s %8s %10.4f %6.2f%% %9s\n", name.c_str(), kind.c_str(),
                  seconds, 100.0 * share, calls.c_str());
    out << line;
  };
  const double loop = profile["loop_seconds"].get<double>();
  for (const nlohmann::json& p : profile["phases"])
    row(p["name"].get<std::string>(), p["kind"].get<std::string>(), p["seconds"].get<double>(),
        p["share"].get<double>(), std::to_string(p["calls"].get<std::int64_t>()));
  const double untimed = profile["untimed_seconds"].get<double>();
  row("untimed (bookkeeping between phases)", "serial", untimed, loop > 0.0 ? untimed / loop : 0.0,
      "-");
  std::snprintf(line, sizeof line,
                "  serial share %.2f%% of the loop: no thread count runs it faster than %.3gx\n",
                100.0 * profile["serial_share"].get<double>(),
                profile["amdahl_limit"].get<double>());
  out << line;
  return out.str();
}

}  // namespace granjet
