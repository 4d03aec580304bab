// A campaign file expanded into its runs and ensembles: every group's product of swept values
// times its seeds, each run with a stable name, its fully resolved scene (every key, as its
// backend runs it) and that scene's hash, by which a finished run is recognised, its files under
// the output directory and an estimate of its cost.
//
//   DIR/<group>/<point>.seed<N>.{ini,h5,json,log}   one run (resolved scene, output, summary, log)
//   DIR/<group>/<point>.{h5,json}                   the ensemble of the point's seeds
//
// <point> names the swept values ("phi_tilde-0.3_friction-0"), or is the group's name when it
// sweeps nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "campaign/campaign_file.hpp"
#include "core/scene.hpp"

namespace granjet {

struct PlanOptions {
  std::filesystem::path out_dir;
  bool quick = false;             // one seed, run.t_end and the analysis window shortened
  std::vector<std::string> only;  // result ids; empty: every group
};

// What a run costs, estimated before it runs.
struct RunCost {
  std::int64_t grains = 0;      // at the start
  std::int64_t steps = 0;       // soft DEM time steps; 0 for the event-driven backend
  double particle_steps = 0.0;  // soft DEM: steps x the grains present on average (jet
                                // grains are removed once they have flowed out)
  double grain_time = 0.0;      // event-driven: the same grains x simulated time
  double seconds = 0.0;         // on one core, from the rates below
};

struct PlannedRun {
  std::size_t group = 0;  // index into CampaignFile::groups
  std::string point;
  std::uint64_t seed = 0;
  std::string name;  // "<group>/<point>.seed<N>": stable, unique, a path under DIR
  std::string backend;
  std::vector<std::string> overrides;    // as --set, in the order applied to the group's scene
  Scene scene;                           // resolved, as the backend runs it (check_backend)
  std::vector<std::string> adaptations;  // what the backend changed of the requested scene
  std::string scene_ini;                 // scene_to_ini(scene)
  std::string hash;                      // of backend and scene_ini
  RunCost cost;
  std::filesystem::path base;  // DIR/<group>/<point>.seed<N> (add .h5, .json, ...)

  std::filesystem::path file(const char* extension) const { return base.string() + extension; }
};

struct PlannedEnsemble {
  std::size_t group = 0;
  std::string point;
  std::string name;               // "<group>/<point>"
  std::vector<std::size_t> runs;  // indices into CampaignPlan::runs, by seed
  std::filesystem::path base;     // DIR/<group>/<point>
  bool analysed = false;          // jet scenes with analysis.enabled: their seeds are combined

  std::filesystem::path file(const char* extension) const { return base.string() + extension; }
};

struct CampaignPlan {
  std::vector<PlannedRun> runs;
  std::vector<PlannedEnsemble> ensembles;
};

// Throws InputError naming "[group] key" for a scene key or value the scene refuses, a backend
// that cannot run the scene, or an --only id that no group serves.
CampaignPlan plan_campaign(const CampaignFile& campaign, const PlanOptions& options);

// FNV-1a (64 bit) of the backend and the resolved scene, as 16 hex digits: a run file whose
// stored scene and backend give the same hash is that run's output.
std::string scene_hash(const std::string& backend, const std::string& scene_ini);

}  // namespace granjet
