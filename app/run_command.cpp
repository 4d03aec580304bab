#include "app/run_command.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "analysis/binary_collision.hpp"
#include "analysis/analysis_json.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/h5md_writer.hpp"
#include "analysis/kinetic_theory.hpp"
#include "app/backend_factory.hpp"
#include "app/ensemble_output.hpp"
#include "app/gas_observer.hpp"
#include "app/interrupts.hpp"
#include "app/inline_analysis.hpp"
#include "app/output_paths.hpp"
#include "app/progress_table.hpp"
#include "app/run_budget.hpp"
#include "app/run_log.hpp"
#include "app/run_warnings.hpp"
#include "app/scene_file.hpp"
#include "app/version.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"

namespace granjet {
namespace {

template <int D>
analysis::Observables observables(const Simulator<D>& sim) {
  const EnergyBalance e = sim.energy();
  return {e.kinetic, e.rotational, e.elastic, e.dissipated,
          static_cast<std::int64_t>(sim.particles().size())};
}

// The H5MD step of a frame: DEM counts time steps, the event-driven backend events.
std::int64_t frame_step(const SimStats& s) { return s.steps > 0 ? s.steps : s.events; }

bool event_driven(const std::string& backend) { return backend == "event_driven"; }

// Hard grains never overlap, so the tracker's gap crossings miss their collision: e from the one
// collision's line of centres and the velocities before (t = 0) and after (the end of the run).
template <int D>
std::optional<double> hard_binary_restitution(const Particles<D>& before, const Particles<D>& after,
                                              const std::vector<PairImpulse<D>>& collisions) {
  if (collisions.size() != 1 || before.size() != 2 || after.size() != 2) return std::nullopt;
  const PairImpulse<D>& c = collisions.front();
  const Vec<D> n = (c.position_j - c.position_i).normalized();
  const auto v_ij = [&](const Particles<D>& p) {
    const std::size_t i = p.id()[0] == c.i ? 0 : 1;
    return Vec<D>(p.velocity()[i] - p.velocity()[1 - i]);
  };
  return -n.dot(v_ij(after)) / n.dot(v_ij(before));
}

// The inline analysis of one run as an ensemble of one: /fields and /analysis in the run's
// file, a .fields.xmf beside it, and the JSON for the summary.
template <int D>
nlohmann::json store_analysis(const InlineAnalysis<D>& fields, const std::filesystem::path& file,
                              const std::filesystem::path& published_as) {
  const std::vector<analysis::RunResult> runs{fields.finish()};
  nlohmann::json j = analysis::to_json(analysis::write_ensemble(file, runs, D, published_as));
  j["seconds"] = fields.seconds();
  return j;
}

template <int D>
nlohmann::json summary_json(const Scene& scene, const std::string& backend,
                            const Simulator<D>& sim, std::int64_t grains_initial,
                            double wall_seconds, const std::string& status) {
  const SimStats s = sim.stats();
  const EnergyBalance e = sim.energy();
  nlohmann::json j;
  j["status"] = status;
  j["scene"] = scene.name;
  j["backend"] = backend;
  j["dimension"] = D;
  j["grains"] = sim.particles().size();
  j["grains_initial"] = grains_initial;
  j["removed"] = s.removed;
  j["time"] = sim.time();
  j["dt"] = scene.dt();
  j["steps"] = s.steps;
  j["contacts"] = s.contacts;
  j["neighbour_rebuilds"] = s.neighbour_rebuilds;
  j["wall_seconds"] = wall_seconds;
  j["particle_steps"] = s.particle_steps;
  j["particle_steps_per_second"] = wall_seconds > 0.0 ? s.particle_steps / wall_seconds : 0.0;
  if (event_driven(backend)) {
    j["events"] = s.events;
    j["collisions"] = s.collisions;
    j["cell_crossings"] = s.cell_crossings;
    j["collisions_per_second"] = wall_seconds > 0.0 ? s.collisions / wall_seconds : 0.0;
  }
  j["energy"] = {{"kinetic", e.kinetic},   {"rotational", e.rotational},
                 {"elastic", e.elastic},   {"removed", e.removed},
                 {"dissipated", e.dissipated}};
  return j;
}

// Who made the run, for H5MD's /h5md/author: --author, else $GRANJET_AUTHOR, else the login.
std::string author_of(const RunOptions& options) {
  if (!options.author.empty()) return options.author;
  for (const char* variable : {"GRANJET_AUTHOR", "USER", "LOGNAME"})
    if (const char* value = std::getenv(variable); value != nullptr && *value != '\0') return value;
  return "granjet user";
}

// Everything of a run that a checkpoint holds besides the simulator: the observers' sums and
// the loop's cursor (the writer adds its frame and row counts).
struct RunCursor {
  double next_output = 0.0;
  double next_progress = 0.0;
  double last_output = 0.0;
  double next_checkpoint = 0.0;
  double wall_seconds = 0.0;  // of the invocations before this one

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("next_output", next_output);
    v("next_progress", next_progress);
    v("last_output", last_output);
    v("next_checkpoint", next_checkpoint);
    v("wall_seconds", wall_seconds);
  }
};

// output.fields may ask only for what the simulator has: hard spheres interact by impulses,
// and only frictional soft grains turn.
template <int D>
void check_output_fields(const Scene& scene, const Simulator<D>& sim) {
  if ((scene.output.force || scene.output.contacts) && !sim.has_contact_forces())
    throw InputError("output.fields",
                     "force and contacts need contact forces; the " + std::string(sim.backend()) +
                         " backend's hard spheres exchange impulses only (use --backend "
                         "soft_dem, or drop them)");
  const bool hard = !sim.has_contact_forces();
  if (scene.output.omega && (hard || !scene.needs_rotation()))
    throw InputError("output.fields", std::string("omega: the grains of this run do not turn (") +
                                          (hard ? "smooth hard spheres" : "contact.friction = 0") +
                                          "); drop it");
}

template <int D>
int run_scene(const Scene& scene, const RunOptions& options, const std::filesystem::path& out_file,
              std::ostream& out, const StateArchive* resume_from) {
  std::unique_ptr<Simulator<D>> sim = make_simulator<D>(options.backend, scene);
  check_output_fields(scene, *sim);
  RunLog log(options.log ? log_path_for(out_file) : std::filesystem::path(),
             resume_from != nullptr, options.quiet ? nullptr : &out);
  log.file() << "# granjet " << kVersion << "+" << kCommit << (resume_from ? " resume " : " run ")
             << (resume_from ? out_file.string() + ".partial" : options.scene_file.string())
             << " --backend " << options.backend;
  for (const std::string& o : options.overrides) log.file() << " --set " << o;
  log.file() << "\n# resolved scene\n" << scene_to_ini(scene) << "# run\n";
  // Said on stderr, and kept in the log.
  const auto say = [&](const std::string& text) {
    std::cerr << "granjet: " << text << "\n";
    log.file() << "granjet: " << text << "\n";
  };
  for (const std::string& note : backend_notes(options.backend, scene)) say(note);
  const std::vector<std::string> warnings = run_warnings(scene, options.backend);
  for (const std::string& warning : warnings) say("warning: " + warning);
  const auto grains_initial = static_cast<std::int64_t>(sim->particles().size());
  const Particles<D> initial = sim->particles();

  const double t_end = scene.run.t_end;
  const double dt = scene.dt();
  const double kInf = std::numeric_limits<double>::infinity();
  const bool binary = scene.kind == SceneKind::kBinary;
  analysis::BinaryCollisionTracker<D> tracker;
  if (binary) sim->record_transfers(true);
  std::optional<GasObserver<D>> gas;
  if (scene.periodic()) gas.emplace(scene, *sim);
  std::optional<InlineAnalysis<D>> fields;
  if (scene.kind == SceneKind::kJet && scene.analysis.enabled) fields.emplace(scene, *sim);
  RunCursor cursor;
  cursor.next_output = scene.output.interval > 0.0 ? scene.output.interval : kInf;
  cursor.next_progress = scene.run.progress_interval;
  cursor.next_checkpoint = scene.run.checkpoint_interval > 0.0 ? scene.run.checkpoint_interval : kInf;
  // The observers' state, one visit for writing a checkpoint and for reading one back.
  const auto visit_observers = [&](auto& visitor) {
    auto run = visitor.nested("run");
    cursor.visit_state(run);
    if (binary) {
      auto v = visitor.nested("tracker");
      tracker.visit_state(v);
    }
    if (gas) {
      auto v = visitor.nested("gas");
      gas->visit_state(v);
    }
    if (fields) {
      auto v = visitor.nested("analysis");
      fields->visit_state(v);
    }
  };

  std::optional<analysis::H5mdWriter<D>> writer;
  ForceSample<D> forces;
  const bool sample_forces = scene.output.force || scene.output.contacts;
  const auto store_frame = [&](std::int64_t step) {
    if (sample_forces) sim->sample_forces(forces);
    writer->write_frame(step, sim->time(), sim->particles(), sample_forces ? &forces : nullptr);
    writer->write_observables(step, sim->time(), observables(*sim));
  };
  if (resume_from) {
    writer.emplace(out_file, typename analysis::H5mdWriter<D>::Resume{});
    writer->replace_scene(scene_to_ini(scene));  // a resume may have extended run.t_end
    sim->restore(*resume_from);
    StateReader reader(*resume_from, "app");
    visit_observers(reader);
    if (sim->time() > t_end)
      throw InputError("run.t_end", std::to_string(t_end) + " lies before the checkpoint at t = " +
                                        std::to_string(sim->time()));
  } else {
    analysis::RunMetadata meta;
    meta.creator_version = std::string(kVersion) + "+" + kCommit;  // semver build metadata
    meta.author = author_of(options);
    meta.backend = options.backend;
    meta.scene_ini = scene_to_ini(scene);
    meta.dimension = D;
    meta.omega = scene.output.omega;
    meta.force = scene.output.force;
    meta.contacts = scene.output.contacts;
    meta.unit_labels = scene.output.unit_labels;
    if (scene.periodic()) {
      const Vec<D> box = gas_lattice<D>(scene.gas).box;
      meta.periodic_box.assign(box.data(), box.data() + D);
    }
    meta.frame_interval = scene.output.interval > 0.0 ? scene.output.interval : t_end;
    writer.emplace(out_file, meta, sim->particles().size());
    store_frame(0);
    if (binary) tracker.observe(sim->particles(), sim->time());
  }
  const auto checkpoint = [&] {
    StateArchive archive;
    sim->checkpoint(archive);
    archive.put("app/time", sim->time());
    StateWriter state(archive, "app");
    visit_observers(state);
    writer->write_checkpoint(archive);
  };

  log.report() << (resume_from ? "continuing " : "writing ") << out_file.string() << " ("
               << options.backend << ", " << D << "D, " << sim->particles().size()
               << " grains, t_end " << t_end << ")\n";
  ProgressTable progress(log.report(), t_end, /*quiet=*/false, event_driven(options.backend));
  const Interrupts interrupts;
  sim->stop_when(&interrupts.stop_flag());
  std::string status = "complete";
  try {
    while (sim->time() < t_end - 0.5 * dt) {
      double target = std::min({t_end, cursor.next_output, cursor.next_progress,
                                cursor.next_checkpoint});
      if (binary) target = std::min(target, sim->time() + dt);  // the tracker samples every step
      if (gas) target = std::min(target, std::max(gas->next_time(), sim->time() + 0.5 * dt));
      if (fields)
        target = std::min(target, std::max(fields->next_time(), sim->time() + 0.5 * dt));
      sim->advance_to(target);
      if (interrupts.signal() != 0) break;  // between the observers' times: none looks
      const double t = sim->time();
      if (binary) tracker.observe(sim->particles(), t);
      if (gas) gas->observe(*sim);
      if (fields) fields->observe(*sim);
      if (t >= cursor.next_output - 0.5 * dt || t >= t_end - 0.5 * dt) {
        store_frame(frame_step(sim->stats()));
        cursor.last_output = t;
        while (cursor.next_output <= t + 0.5 * dt) cursor.next_output += scene.output.interval;
      }
      if (t >= cursor.next_progress - 0.5 * dt) {
        progress.row(t, static_cast<std::int64_t>(sim->particles().size()), sim->stats(),
                     sim->energy());
        while (cursor.next_progress <= t + 0.5 * dt)
          cursor.next_progress += scene.run.progress_interval;
      }
      if (t >= cursor.next_checkpoint - 0.5 * dt && t < t_end - 0.5 * dt) {
        while (cursor.next_checkpoint <= t + 0.5 * dt)
          cursor.next_checkpoint += scene.run.checkpoint_interval;
        const double earlier = cursor.wall_seconds;
        cursor.wall_seconds += progress.elapsed_seconds();  // as the checkpoint's
        checkpoint();
        cursor.wall_seconds = earlier;
      }
    }
    if (interrupts.signal() != 0) {
      cursor.wall_seconds += progress.elapsed_seconds();
      checkpoint();
      status = "interrupted";
      const std::filesystem::path kept = writer->abandon(status);
      std::ostringstream text;
      text << "interrupted (signal " << interrupts.signal() << ") at t = " << sim->time()
           << "; the run is kept in " << kept.string()
           << "; go on with: granjet resume " << kept.string();
      say(text.str());
    } else if (cursor.last_output < sim->time()) {
      store_frame(frame_step(sim->stats()));
    }
  } catch (const BlowUpError& e) {
    const std::filesystem::path kept = writer->abandon(e.what());
    say(e.what());
    say("frames written so far are kept in " + kept.string());
    status = e.what();
  }
  const double wall =
      cursor.wall_seconds + (status == "interrupted" ? 0.0 : progress.elapsed_seconds());
  nlohmann::json summary = summary_json(scene, options.backend, *sim, grains_initial, wall, status);
  if (!warnings.empty()) summary["warnings"] = warnings;
  if (binary && tracker.complete()) {
    summary["measured"] = {{"restitution", tracker.restitution()},
                           {"contact_time", tracker.contact_time()}};
    summary["requested"] = {{"restitution", scene.contact.restitution},
                            {"contact_time", scene.contact.contact_time}};
  } else if (binary) {
    std::vector<PairImpulse<D>> collisions;
    sim->collect_transfers(collisions);
    if (const auto e = hard_binary_restitution(initial, sim->particles(), collisions)) {
      summary["measured"] = {{"restitution", *e}};
      summary["requested"] = {{"restitution", scene.contact.restitution}};
    }
  }
  if (gas && gas->samples() > 1) {
    namespace kinetic = analysis::kinetic;
    summary["measured"] = {{"temperature", gas->temperature()}};
    if (scene.kind == SceneKind::kGas) {
      summary["measured"]["compressibility"] = gas->compressibility();
      // Elastic hard spheres: Carnahan-Starling; hard disks: Henderson.
      summary["theory"] = {{"compressibility", D == 3 ? kinetic::carnahan_starling(scene.gas.phi)
                                                      : kinetic::henderson(scene.gas.phi)}};
    } else {
      // Backend-neutral: -d ln T/dt at gas.temperature (the soft backend counts contacts, not
      // collisions).
      summary["measured"]["cooling_rate"] = gas->cooling_rate(scene.gas.temperature);
      if (sim->stats().collisions > 0) {
        summary["measured"]["cooling_per_collision"] = gas->cooling_per_collision();
        summary["theory"] = {{"cooling_per_collision",
                              kinetic::cooling_per_collision(scene.contact.restitution, D)}};
      }
    }
  }
  // Everything the run produced goes into its .partial and the sidecars first; the rename to
  // the final name comes last, so a file under that name is complete.
  std::optional<std::filesystem::path> partial;
  if (status == "complete") {
    partial = writer->complete();
    summary["output"] = out_file.string();
    // A window that never opened (t_end before its start) measured nothing: no all-NaN fields.
    if (fields && fields->window_sampled())
      summary["analysis"] = store_analysis<D>(*fields, *partial, out_file);
    else if (fields)  // run_warnings said so before the run
      say("no fields written: the analysis window never started");
  }
  {
    std::ostringstream timing;
    const SimStats s = sim->stats();
    if (event_driven(options.backend))
      timing << "loop time " << wall << " s for " << s.events << " events (" << s.collisions
             << " collisions, " << s.cell_crossings << " cell crossings), "
             << summary["collisions_per_second"].get<double>() << " collisions/s\n";
    else
      timing << "loop time " << wall << " s for " << s.steps << " steps, "
             << summary["particle_steps_per_second"].get<double>() << " particle-steps/s\n";
    if (summary.contains("measured")) {
      timing << "measured";
      for (const auto& [key, value] : summary["measured"].items())
        timing << " " << key << " " << value;
      if (summary.contains("theory"))
        for (const auto& [key, value] : summary["theory"].items())
          timing << " (theory " << key << " " << value << ")";
      timing << "\n";
    }
    // A failed run reports even when quiet.
    log.report() << timing.str();
    if (options.quiet && status != "complete") out << timing.str();
  }
  {
    // The analysis' bins would be thousands of lines indented: one line of its own instead.
    nlohmann::json brief = summary;
    brief.erase("analysis");
    log.file() << "# summary\n" << brief.dump(2) << "\n";
    if (summary.contains("analysis"))
      log.file() << "# summary: analysis\n" << summary["analysis"].dump() << "\n";
  }
  if (!options.summary.empty()) write_json_atomically(options.summary, summary);
  if (partial) {
    writer->publish();
    log.report() << "wrote " << out_file.string() << "\n";
  }
  if (status == "interrupted") return 128 + interrupts.signal();
  return status == "complete" ? 0 : 3;
}

}  // namespace

// The same scene once per seed, then the analysis combined over the seeds from the run files
// (spec §5: error bars are the spread over independent initial configurations).
template <int D>
int run_ensemble(const Scene& scene, const RunOptions& options,
                 const std::filesystem::path& out_file, std::ostream& out) {
  std::vector<EnsembleMember> members;
  int worst = 0;
  for (const std::uint64_t seed : options.seeds) {
    Scene one = scene;
    one.run.seed = seed;
    RunOptions o = options;
    o.summary = member_file(options.summary, seed);
    if (!options.quiet) out << "seed " << seed << "\n";
    const std::filesystem::path file = member_file(out_file, seed);
    const int code = run_scene<D>(one, o, file, out, nullptr);
    if (code >= 128) return code;  // interrupted: the other seeds wait too
    worst = std::max(worst, code);
    members.push_back({seed, file});
  }
  const nlohmann::json header = {{"scene", scene.name}, {"backend", options.backend}, {"dimension", D}};
  const int combined = merge_ensemble(out_file, options.summary, header, members, D);
  if (combined > 0)
    out << "ensemble of " << combined << " seeds: /fields and /analysis in " << out_file.string()
        << "\n";
  return worst;
}

// What a resume may change: how long the run goes on, how it reports, and the thread count
// (the results do not depend on it). Anything else would make it another run.
const std::vector<std::string> kResumableKeys = {"run.t_end", "run.threads",
                                                  "run.progress_interval"};

int resume_command(const ResumeOptions& options, std::ostream& out) {
  const std::filesystem::path& partial = options.partial;
  if (partial.extension() != ".partial")
    throw InputError(partial.string(), "is not a run's .partial file (RUN.h5.partial)");
  const analysis::FileSummary stored = analysis::read_summary(partial);
  if (!stored.checkpoint)
    throw InputError(partial.string(), "holds no checkpoint: the run stopped before its first "
                                       "run.checkpoint_interval; run it again");
  for (const std::string& assignment : options.overrides) {
    const std::string key = assignment.substr(0, assignment.find('='));
    if (std::find(kResumableKeys.begin(), kResumableKeys.end(), key) == kResumableKeys.end())
      throw InputError(key, "cannot change on resume (it would make another run); allowed: "
                            "run.t_end, run.threads, run.progress_interval");
  }
  std::istringstream ini(stored.scene_ini);
  const Scene scene = parse_scene(ini, partial.string() + " (stored scene)", options.overrides);
  if (scene.run.t_end < stored.checkpoint_time)
    throw InputError("run.t_end", std::to_string(scene.run.t_end) +
                                      " lies before the checkpoint at t = " +
                                      std::to_string(stored.checkpoint_time));
  check_run_budget(scene, stored.backend, physical_memory_bytes());
  RunOptions run;
  run.backend = stored.backend;
  run.summary = options.summary;
  run.quiet = options.quiet;
  run.log = options.log;
  const std::filesystem::path out_file = std::filesystem::path(partial).replace_extension();
  std::vector<OutputPath> outputs = run_outputs(out_file, run.summary);
  std::erase_if(outputs, [&](const OutputPath& o) { return o.path == partial; });
  check_outputs(partial, outputs);
  const StateArchive checkpoint = analysis::read_checkpoint(partial);
  if (!options.quiet)
    out << "resuming " << out_file.string() << " at t = " << stored.checkpoint_time << "\n";
  return scene.dimension == 2 ? run_scene<2>(scene, run, out_file, out, &checkpoint)
                              : run_scene<3>(scene, run, out_file, out, &checkpoint);
}

int run_command(const RunOptions& options, std::ostream& out) {
  const Scene scene = load_scene(options.scene_file, options.overrides);
  check_backend(options.backend, scene);
  check_run_budget(scene, options.backend, physical_memory_bytes());
  std::filesystem::path out_file = options.out;
  if (out_file.empty()) out_file = options.scene_file.stem().string() + ".h5";
  std::vector<OutputPath> outputs = run_outputs(out_file, options.summary);
  for (const std::uint64_t seed : options.seeds)
    for (OutputPath& o : run_outputs(member_file(out_file, seed), member_file(options.summary, seed),
                                     "seed " + std::to_string(seed) + "'s"))
      outputs.push_back(std::move(o));
  check_outputs(options.scene_file, outputs);
  if (!options.seeds.empty())
    return scene.dimension == 2 ? run_ensemble<2>(scene, options, out_file, out)
                                : run_ensemble<3>(scene, options, out_file, out);
  return scene.dimension == 2 ? run_scene<2>(scene, options, out_file, out, nullptr)
                              : run_scene<3>(scene, options, out_file, out, nullptr);
}

}  // namespace granjet
