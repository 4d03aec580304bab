#include "campaign/campaign_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "core/jet_geometry.hpp"
#include "run/backend_factory.hpp"
#include "run/run_budget.hpp"
#include "run/scene_file.hpp"
#include "run/scene_kinds.hpp"

namespace granjet {
namespace {

std::string exact(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// An InputError raised while resolving a group's scene, renamed to point into the campaign file.
[[noreturn]] void rethrow_in_group(const InputError& e, const CampaignGroup& g) {
  const std::string prefix = e.key() + ": ";
  const std::string what = e.what();
  const std::string message = what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
  const bool about_file = e.key() == g.scene.string();
  const std::string key = about_file ? "scene" : e.key() == "--backend" ? "backend" : e.key();
  throw InputError("[" + g.name + "] " + key,
                   (about_file ? g.scene.string() + ": " : "") + message);
}

// The label of one combination of swept values: "<key>-<value>" joined by "_", each key by its
// last part unless two swept keys of the group share it.
std::string point_label(const std::vector<const CampaignKey*>& swept,
                        const std::vector<std::size_t>& choice) {
  const auto short_name = [](const std::string& key) { return key.substr(key.rfind('.') + 1); };
  bool shared = false;
  for (std::size_t a = 0; a < swept.size(); ++a)
    for (std::size_t b = a + 1; b < swept.size(); ++b)
      shared |= short_name(swept[a]->key) == short_name(swept[b]->key);
  std::string label;
  for (std::size_t k = 0; k < swept.size(); ++k)
    label += (k ? "_" : "") + (shared ? swept[k]->key : short_name(swept[k]->key)) + "-" +
             swept[k]->values[choice[k]];
  return label;
}

// --quick: the same scene over a fraction of its simulated time, the windows scaled alike.
std::vector<std::string> quick_overrides(const Scene& s, double fraction) {
  std::vector<std::string> o{"run.t_end=" + exact(fraction * s.run.t_end)};
  for (const auto& [key, time] : scene_kind(s.kind).scaled_times(s))
    o.push_back(key + "=" + exact(fraction * time));
  return o;
}

// Grains and the mean number of them present over the run. Jet grains leave the region once
// they have hit the target and flowed out: the column is used up at u0, so the last grain leaves
// about (column length + region.radius)/u0 after the start, and on average half the column is
// there while it is being used up.
template <int D>
std::pair<std::int64_t, double> grains_over_run(const Scene& scene) {
  const Particles<D> p = build_initial_state<D>(scene);
  const auto total = static_cast<std::int64_t>(p.size());
  if (scene.kind != SceneKind::kJet) return {total, static_cast<double>(total)};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, jet = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] != GrainKind::kWall) {
      lo = std::min(lo, p.position()[i][kJetAxis<D>]);
      hi = std::max(hi, p.position()[i][kJetAxis<D>]);
      jet += 1.0;
    }
  const double used_up = (hi - lo + scene.region.radius) / scene.jet.speed;
  const double t = scene.run.t_end;
  const double present = t < used_up ? 1.0 - t / (2.0 * used_up) : used_up / (2.0 * t);
  return {total, static_cast<double>(total) - jet * (1.0 - present)};
}

RunCost estimate_cost(const Scene& scene, const std::string& backend) {
  RunCost c;
  const auto [grains, mean_grains] =
      with_dimension(scene.dimension, [&](auto d) { return grains_over_run<d>(scene); });
  c.grains = grains;
  const Backend& b = backend_named(backend);
  const double rate = scene.dimension == 2 ? b.rate_2d : b.rate_3d;
  if (b.counts_events) {
    c.grain_time = mean_grains * scene.run.t_end;
    c.seconds = c.grain_time / rate;
  } else {
    c.steps = static_cast<std::int64_t>(std::ceil(scene.run.t_end / scene.dt() - 0.5));
    c.particle_steps = mean_grains * static_cast<double>(c.steps);
    c.seconds = c.particle_steps / rate;
  }
  return c;
}

bool serves_any(const CampaignGroup& g, const std::vector<std::string>& ids) {
  for (const std::string& id : ids)
    if (std::find(g.results.begin(), g.results.end(), id) != g.results.end()) return true;
  return false;
}

void check_only(const CampaignFile& campaign, const std::vector<std::string>& only) {
  std::vector<std::string> known;
  for (const CampaignGroup& g : campaign.groups)
    for (const std::string& id : g.results)
      if (std::find(known.begin(), known.end(), id) == known.end()) known.push_back(id);
  for (const std::string& id : only)
    if (std::find(known.begin(), known.end(), id) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError("--only", "'" + id + "' is served by no group of " + campaign.file.string() +
                                     "; its results: " + list);
    }
}

// The group's runs and ensembles, appended to `plan`.
void plan_group(const CampaignFile& campaign, std::size_t index, const PlanOptions& options,
                CampaignPlan& plan) {
  const CampaignGroup& g = campaign.groups[index];
  std::vector<const CampaignKey*> swept;
  std::vector<std::string> fixed;
  for (const CampaignKey& k : g.keys) {
    if (k.values.size() > 1)
      swept.push_back(&k);
    else
      fixed.push_back(k.key + "=" + k.values.front());
  }
  std::vector<std::size_t> choice(swept.size(), 0);
  std::vector<std::string> points_seen;
  while (true) {
    std::vector<std::string> overrides = fixed;
    for (std::size_t k = 0; k < swept.size(); ++k)
      overrides.push_back(swept[k]->key + "=" + swept[k]->values[choice[k]]);
    PlannedEnsemble ensemble;
    ensemble.group = index;
    ensemble.point = swept.empty() ? g.name : point_label(swept, choice);
    ensemble.name = g.name + "/" + ensemble.point;
    ensemble.base = options.out_dir / g.name / ensemble.point;
    if (std::find(points_seen.begin(), points_seen.end(), ensemble.point) != points_seen.end())
      throw InputError("[" + g.name + "] " + swept.front()->key,
                       "a swept value is listed twice (" + ensemble.point + ")");
    points_seen.push_back(ensemble.point);

    Scene base_scene;
    try {
      base_scene = load_scene(g.scene, overrides);
    } catch (const InputError& e) {
      rethrow_in_group(e, g);
    }
    std::vector<std::uint64_t> seeds = g.seeds;
    if (seeds.empty()) seeds.push_back(base_scene.run.seed);
    if (options.quick) seeds.resize(1);
    ensemble.analysed = base_scene.kind == SceneKind::kJet && base_scene.analysis.enabled;
    std::optional<RunCost> point_cost;  // the seeds differ only in which sites are kept
    for (const std::uint64_t seed : seeds) {
      PlannedRun run;
      run.group = index;
      run.point = ensemble.point;
      run.seed = seed;
      run.name = ensemble.name + ".seed" + std::to_string(seed);
      run.backend = g.backend;
      run.overrides = overrides;
      run.overrides.push_back("run.seed=" + std::to_string(seed));
      if (options.quick)
        for (const std::string& o : quick_overrides(base_scene, g.quick_fraction))
          run.overrides.push_back(o);
      try {
        const SceneSupport support = check_backend(run.backend, load_scene(g.scene, run.overrides));
        run.scene = support.resolved;
        for (const SceneSupport::Adaptation& a : support.adaptations)
          run.adaptations.push_back(describe(run.backend, a));
        check_run_budget(run.scene, run.backend, physical_memory_bytes());
      } catch (const InputError& e) {
        rethrow_in_group(e, g);
      }
      run.scene_ini = scene_to_ini(run.scene);
      run.hash = scene_hash(run.backend, run.scene_ini);
      if (!point_cost) point_cost = estimate_cost(run.scene, run.backend);
      run.cost = *point_cost;
      run.base = options.out_dir / g.name / (ensemble.point + ".seed" + std::to_string(seed));
      ensemble.runs.push_back(plan.runs.size());
      plan.runs.push_back(std::move(run));
    }
    plan.ensembles.push_back(std::move(ensemble));
    // The next combination; the first swept key varies slowest.
    std::size_t k = swept.size();
    while (k > 0 && ++choice[k - 1] == swept[k - 1]->values.size()) choice[--k] = 0;
    if (k == 0) break;
  }
}

}  // namespace

std::string scene_hash(const std::string& backend, const std::string& scene_ini) {
  std::uint64_t h = 14695981039346656037ull;
  const auto mix = [&h](const std::string& text) {
    for (const unsigned char c : text) {
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  mix(backend);
  mix("\n");
  mix(scene_ini);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

CampaignPlan plan_campaign(const CampaignFile& campaign, const PlanOptions& options) {
  check_only(campaign, options.only);
  CampaignPlan plan;
  for (std::size_t g = 0; g < campaign.groups.size(); ++g)
    if (options.only.empty() || serves_any(campaign.groups[g], options.only))
      plan_group(campaign, g, options, plan);
  return plan;
}

}  // namespace granjet
