// DIR/manifest.json: what a campaign ran, when, where and at which commit. Kept across reruns
// (each invocation appends itself; a run's entry is replaced when it runs again) and rewritten
// atomically after every change, so an interrupted campaign's manifest is still true.
//
//   { "campaign", "file", "description",
//     "invocations": [{"started", "finished", "host", "version", "commit", "command", "jobs",
//                      "ranks", "quick", "only", "planned", "found_complete", "executed",
//                      "complete", "blown_up", "failed", "wall_seconds"}],
//     "runs": {"<group>/<point>.seed<N>": {"group", "point", "seed", "backend", "results",
//              "hash", "overrides", "status" (pending | running | complete | blown_up |
//              failed), "exit_code", "wall_seconds", "host", "rank", "started", "finished",
//              "output", "summary", "log", "cost": {...}}},
//     "ensembles": {"<group>/<point>": {"group", "point", "seeds", "hashes", "combined",
//                   "output", "summary"}} }
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace granjet {

class CampaignManifest {
 public:
  // Reads DIR/manifest.json when there is one (an unreadable one is set aside as
  // manifest.json.broken and a new one begun).
  explicit CampaignManifest(const std::filesystem::path& dir);

  nlohmann::json& json() { return json_; }
  nlohmann::json& run(const std::string& name) { return json_["runs"][name]; }
  nlohmann::json& ensemble(const std::string& name) { return json_["ensembles"][name]; }
  nlohmann::json& invocation() { return json_["invocations"].back(); }
  void save() const;

 private:
  std::filesystem::path file_;
  nlohmann::json json_;
};

// Now, in UTC, as 2026-11-23T19:16:02Z.
std::string utc_now();

}  // namespace granjet
