#include "run/run_command.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "analysis/checkpoint_file.hpp"
#include "analysis/field_accumulator.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/h5md_writer.hpp"
#include "analysis/inline_analysis.hpp"
#include "analysis/run_analysis.hpp"
#include "core/errors.hpp"
#include "core/initial_state.hpp"
#include "core/rank_team.hpp"
#include "run/backend_factory.hpp"
#include "run/checkpoint_schedule.hpp"
#include "run/ensemble_output.hpp"
#include "run/failure_report.hpp"
#include "run/frame_output.hpp"
#include "run/interrupts.hpp"
#include "run/output_paths.hpp"
#include "run/progress_rows.hpp"
#include "run/rank_leader.hpp"
#include "run/run_budget.hpp"
#include "run/run_log.hpp"
#include "run/run_loop.hpp"
#include "run/run_profile.hpp"
#include "run/run_warnings.hpp"
#include "run/scene_file.hpp"
#include "run/scene_kinds.hpp"
#include "run/version.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/scene_support.hpp"

namespace granjet {
namespace {

template <int D>
nlohmann::json summary_json(const Scene& scene, const Backend& backend, const Simulator<D>& sim,
                            std::int64_t grains_initial, double wall_seconds, double cpu_seconds,
                            const std::string& status) {
  const SimStats s = sim.stats();
  const EnergyBalance e = sim.energy();
  nlohmann::json j;
  j["status"] = status;
  j["scene"] = scene.name;
  j["backend"] = backend.name;
  j["dimension"] = D;
  j["grains"] = sim.grain_count();
  j["grains_initial"] = grains_initial;
  j["removed"] = s.removed;
  j["time"] = sim.time();
  j["dt"] = scene.dt();
  j["steps"] = s.steps;
  j["contacts"] = s.contacts;
  j["neighbour_rebuilds"] = s.neighbour_rebuilds;
  if (s.ranks > 1)
    j["ranks"] = {{"count", s.ranks},
                  {"imbalance", s.imbalance},
                  {"recuts", s.recuts},
                  {"ghost_states_per_step", s.ghost_states_per_step},
                  {"ghost_states_share", s.ghost_states_share}};
  j["wall_seconds"] = wall_seconds;
  j["cpu_seconds"] = cpu_seconds;  // of all threads: the rates below are per wall-second
  j["particle_steps"] = s.particle_steps;
  j["particle_steps_per_second"] = wall_seconds > 0.0 ? s.particle_steps / wall_seconds : 0.0;
  if (backend.counts_events) {
    j["events"] = s.events;
    j["collisions"] = s.collisions;
    j["cell_crossings"] = s.cell_crossings;
    j["collisions_per_second"] = wall_seconds > 0.0 ? s.collisions / wall_seconds : 0.0;
  }
  j["energy"] = {{"kinetic", e.kinetic},
                 {"rotational", e.rotational},
                 {"elastic", e.elastic},
                 {"removed", e.removed},
                 {"dissipated", e.dissipated}};
  return j;
}

// The lines that close a run: the loop's time and rate, and what it measured.
std::string timing_text(const nlohmann::json& summary, const SimStats& s, bool events, double wall,
                        double cpu) {
  std::ostringstream timing;
  timing << "loop time " << wall << " s (CPU " << cpu << " s)";
  if (events)
    timing << " for " << s.events << " events (" << s.collisions << " collisions, "
           << s.cell_crossings << " cell crossings), "
           << summary["collisions_per_second"].get<double>() << " collisions/s\n";
  else
    timing << " for " << s.steps << " steps, " << summary["particle_steps_per_second"].get<double>()
           << " particle-steps/s\n";
  if (s.ranks > 1)
    timing << "over " << s.ranks << " ranks: imbalance " << s.imbalance
           << " (the busiest rank's work over the mean), parts cut anew " << s.recuts
           << " times; ghost states sent " << s.ghost_states_per_step << " a step, "
           << 100.0 * s.ghost_states_share << "% of the ghosts held (the others coasted)\n";
  if (summary.contains("measured")) {
    timing << "measured";
    for (const auto& [key, value] : summary["measured"].items())
      timing << " " << key << " " << value;
    if (summary.contains("theory"))
      for (const auto& [key, value] : summary["theory"].items())
        timing << " (theory " << key << " " << value << ")";
    timing << "\n";
  }
  return timing.str();
}

// The summary at the end of the log; the analysis' bins would be thousands of lines indented:
// one line of their own instead.
void log_summary(RunLog& log, const nlohmann::json& summary) {
  nlohmann::json brief = summary;
  brief.erase("analysis");
  log.file() << "# summary\n" << brief.dump(2) << "\n";
  if (summary.contains("analysis"))
    log.file() << "# summary: analysis\n" << summary["analysis"].dump() << "\n";
}

// Who made the run, for H5MD's /h5md/author: --author, else $GRANJET_AUTHOR, else the login.
std::string author_of(const RunOptions& options) {
  if (!options.author.empty()) return options.author;
  for (const char* variable : {"GRANJET_AUTHOR", "USER", "LOGNAME"})
    if (const char* value = std::getenv(variable); value != nullptr && *value != '\0') return value;
  return "granjet user";
}

// What the backend changed of the requested scene, for the summary.
nlohmann::json adaptations_json(const SceneSupport& support) {
  nlohmann::json list = nlohmann::json::array();
  for (const SceneSupport::Adaptation& a : support.adaptations)
    list.push_back({{"key", a.key},
                    {"requested", a.requested},
                    {"resolved", a.resolved},
                    {"reason", a.reason}});
  return list;
}

// The requested scene as the run's file keeps it: only where the backend adapted it.
std::string requested_ini(const Scene& requested, const SceneSupport& support) {
  return support.adaptations.empty() ? std::string() : scene_to_ini(requested);
}

template <int D>
analysis::RunMetadata run_metadata(const Scene& scene, const std::string& requested_scene_ini,
                                   const RunOptions& options) {
  analysis::RunMetadata meta;
  meta.creator_version = std::string(kVersion) + "+" + kCommit;  // semver build metadata
  meta.author = author_of(options);
  meta.backend = options.backend;
  meta.scene_ini = scene_to_ini(scene);
  meta.requested_scene_ini = requested_scene_ini;
  meta.dimension = D;
  meta.omega = scene.output.omega;
  meta.force = scene.output.force;
  meta.contacts = scene.output.contacts;
  meta.unit_labels = scene.output.unit_labels;
  if (scene.periodic()) {
    const Vec<D> box = gas_lattice<D>(scene.gas).box;
    meta.periodic_box.assign(box.data(), box.data() + D);
  }
  meta.frame_interval = scene.output.interval > 0.0 ? scene.output.interval : scene.run.t_end;
  return meta;
}

// The head of the run's log: the command, and the scene as the backend runs it.
void write_log_head(RunLog& log, const RunOptions& options, const Scene& scene,
                    const std::filesystem::path& out_file, bool resuming) {
  log.file() << "# granjet " << kVersion << "+" << kCommit << (resuming ? " resume " : " run ")
             << (resuming ? out_file.string() + ".partial" : options.scene_file.string())
             << " --backend " << options.backend;
  for (const std::string& o : options.overrides) log.file() << " --set " << o;
  log.file() << "\n# resolved scene\n" << scene_to_ini(scene) << "# run\n";
}

// The run's file: a new one, or a resumed run's .partial, whose scenes are stored again (a
// resume may have extended run.t_end).
template <int D>
std::unique_ptr<analysis::H5mdWriter<D>> open_run_file(const std::filesystem::path& out_file,
                                                       const Scene& scene,
                                                       const std::string& requested_scene_ini,
                                                       const RunOptions& options,
                                                       std::size_t grains, bool resuming) {
  using Writer = analysis::H5mdWriter<D>;
  if (!resuming)
    return std::make_unique<Writer>(out_file, run_metadata<D>(scene, requested_scene_ini, options),
                                    grains);
  auto writer = std::make_unique<Writer>(out_file, typename Writer::Resume{});
  writer->replace_scenes(scene_to_ini(scene), requested_scene_ini);
  return writer;
}

// Said on stderr, and kept in the log.
using Say = std::function<void(const std::string&)>;

// The observers' loop to t_end, and the run's file ended as the loop ended. Returns the run's
// status: "complete" (with its last frame), "interrupted" (a checkpoint written, the file kept
// as .partial) or the blow-up's message (the file kept as .partial).
template <int D>
std::string observe_to_end(Simulator<D>& sim, const Scene& scene, const RunObservers<D>& observers,
                           FrameOutput<D>& frames, analysis::H5mdWriter<D>& writer,
                           const Interrupts& interrupts, bool checkpoint_on_signal,
                           const Say& say) {
  try {
    observe_until(sim, scene.run.t_end, 0.5 * scene.dt(), observers, interrupts);
  } catch (const BlowUpError& e) {
    const std::filesystem::path kept = writer.abandon(e.what());
    say(e.what());
    say("frames written so far are kept in " + kept.string());
    return e.what();
  }
  if (interrupts.signal() == 0) {
    frames.finish(sim);
    return "complete";
  }
  if (checkpoint_on_signal) write_checkpoint(sim, observers, writer);
  const std::filesystem::path kept = writer.abandon("interrupted");
  std::ostringstream text;
  text << "interrupted (signal " << interrupts.signal() << ") at t = " << sim.time()
       << "; the run is kept in " << kept.string() << "; go on with: granjet resume "
       << kept.string();
  if (!checkpoint_on_signal) text << " (from its last scheduled checkpoint, if any)";
  say(text.str());
  return "interrupted";
}

}  // namespace

template <int D>
RunOutcome run_simulation(Simulator<D>& sim, const Scene& requested, const SceneSupport& support,
                          const RunOptions& options, const std::filesystem::path& out_file,
                          std::ostream& out, const StateArchive* resume_from) {
  const Backend& backend = backend_named(options.backend);
  const Scene& scene = support.resolved;
  RunLog log(options.log ? log_path_for(out_file) : std::filesystem::path(), resume_from != nullptr,
             options.quiet ? nullptr : &out);
  write_log_head(log, options, scene, out_file, resume_from != nullptr);
  const Say say = [&](const std::string& text) {
    std::cerr << "granjet: " << text << "\n";
    log.file() << "granjet: " << text << "\n";
  };
  for (const SceneSupport::Adaptation& a : support.adaptations) say(describe(backend.name, a));
  for (const std::string& note : support.notes) say(backend.name + ": " + note);
  const std::vector<std::string> warnings = run_warnings(scene, backend);
  for (const std::string& warning : warnings) say("warning: " + warning);
  const auto grains_initial = static_cast<std::int64_t>(sim.grain_count());

  const std::vector<std::unique_ptr<analysis::RunObserver<D>>> measurements =
      scene_measurements(scene, sim);
  const std::unique_ptr<analysis::H5mdWriter<D>> writer =
      open_run_file<D>(out_file, scene, requested_ini(requested, support), options,
                       sim.grain_count(), resume_from != nullptr);
  FrameOutput<D> frames(*writer, scene);
  ProgressRows<D> progress(log.report(), scene, backend.counts_events);
  RunObservers<D> observers;
  CheckpointSchedule<D> checkpoints(scene, [&] { write_checkpoint(sim, observers, *writer); });
  for (const auto& m : measurements) observers.push_back(m.get());
  observers.insert(observers.end(), {&frames, &progress, &checkpoints});
  if (resume_from) {
    restore_checkpoint(sim, observers, *resume_from);
    if (sim.time() > scene.run.t_end)
      throw InputError("run.t_end",
                       std::to_string(scene.run.t_end) +
                           " lies before the checkpoint at t = " + std::to_string(sim.time()));
  } else {
    frames.start(sim);
  }

  log.report() << (resume_from ? "continuing " : "writing ") << out_file.string() << " ("
               << backend.name << ", " << D << "D, " << sim.grain_count() << " grains, t_end "
               << scene.run.t_end << ")\n";
  progress.header();
  const Interrupts interrupts;
  sim.stop_when(&interrupts.stop_flag());
  if (options.profile) sim.profile().enable();
  const auto loop_start = std::chrono::steady_clock::now();
  const std::string status = observe_to_end(sim, scene, observers, frames, *writer, interrupts,
                                            options.checkpoint_on_signal, say);
  sim.stop_when(nullptr);  // the flag goes with `interrupts`; the simulator may live on
  const double loop_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();

  const double wall = progress.wall_seconds();
  const double cpu = progress.cpu_seconds();
  nlohmann::json summary = summary_json(scene, backend, sim, grains_initial, wall, cpu, status);
  if (!warnings.empty()) summary["warnings"] = warnings;
  if (!support.adaptations.empty()) summary["adaptations"] = adaptations_json(support);
  for (analysis::RunObserver<D>* o : observers) o->summarize(sim, summary);
  // Everything the run produced goes into its .partial and the sidecars first; the rename to
  // the final name comes last, so a file under that name is complete.
  if (status == "complete") {
    const std::filesystem::path partial = writer->complete();
    summary["output"] = out_file.string();
    for (analysis::RunObserver<D>* o : observers)
      if (const std::string line = o->store(partial, out_file, summary); !line.empty()) say(line);
  }
  const std::string timing = timing_text(summary, sim.stats(), backend.counts_events, wall, cpu);
  log.report() << timing;
  if (options.profile) {
    summary["profile"] =
        profile_json(sim.profile(), loop_seconds, scene.run.threads, sim.phase_seconds_by_rank());
    const std::string table = profile_text(summary["profile"]);
    log.report() << table;
    if (options.quiet) out << table;  // asked for: shown even without progress rows
  }
  if (options.quiet && status != "complete") out << timing;  // a failed run reports even so
  log_summary(log, summary);
  if (!options.summary.empty()) write_json_atomically(options.summary, summary);
  if (status == "complete") {
    writer->publish();
    log.report() << "wrote " << out_file.string() << "\n";
  }
  if (status == "interrupted") return {128 + interrupts.signal(), summary};
  return {status == "complete" ? 0 : 3, summary};
}

template RunOutcome run_simulation<2>(Simulator<2>&, const Scene&, const SceneSupport&,
                                      const RunOptions&, const std::filesystem::path&,
                                      std::ostream&, const StateArchive*);
template RunOutcome run_simulation<3>(Simulator<3>&, const Scene&, const SceneSupport&,
                                      const RunOptions&, const std::filesystem::path&,
                                      std::ostream&, const StateArchive*);

namespace {

// A rank other than 0 of a run spread over ranks: builds its share of the grains and makes
// each call rank 0 makes. An error here would end every rank (MpiSession) before rank 0 could
// name it, so this rank names it.
template <int D>
void follow(const Scene& resolved, const RunOptions& options, const RankTeam& ranks,
            const StateArchive* resume_from) {
  try {
    const std::unique_ptr<Simulator<D>> sim = dem::make_dem_simulator<D>(resolved, ranks);
    if (options.profile) sim->profile().enable();  // rank 0 shows the spread over ranks
    // An interrupt is rank 0's to handle: it stops every rank at the same step.
    std::signal(SIGINT, SIG_IGN);
    std::signal(SIGTERM, SIG_IGN);
    // This rank's part of the inline analysis' bins (analysis::InlineAnalysis on rank 0).
    std::optional<analysis::FieldAccumulator<D>> bins;
    if (resolved.kind == SceneKind::kJet && resolved.analysis.enabled)
      bins.emplace(analysis::AnalysisConfig::for_scene(resolved).bins);
    follow_leader<D>(*sim, ranks, resume_from, bins ? &*bins : nullptr,
                     analysis::InlineAnalysis<D>::bins_state(kObserverStates));
  } catch (const std::exception& e) {
    std::cerr << "granjet: rank " << ranks.rank() << ": " << e.what() << "\n";
    throw;
  }
}

// One run of the scene as the backend resolves it, into `out_file`. Started as several MPI
// ranks, the soft DEM spreads it over them: rank 0 runs and writes it, the others follow.
template <int D>
int run_scene(const Scene& requested, const RunOptions& options,
              const std::filesystem::path& out_file, std::ostream& out,
              const StateArchive* resume_from) {
  const SceneSupport support = check_backend(options.backend, requested);
  const RankTeam ranks = RankTeam::world();
  if (ranks.alone()) {
    const std::unique_ptr<Simulator<D>> sim = make_simulator<D>(options.backend, support.resolved);
    return run_simulation<D>(*sim, requested, support, options, out_file, out, resume_from)
        .exit_code;
  }
  if (ranks.rank() != 0) {
    follow<D>(support.resolved, options, ranks, resume_from);
    return 0;
  }
  RankLeader<D> leader(dem::make_dem_simulator<D>(support.resolved, ranks), ranks);
  return run_simulation<D>(leader, requested, support, options, out_file, out, resume_from)
      .exit_code;
}

// What every rank checks of the scene before a run or a resume starts: that the backend runs it,
// on as many ranks as mpirun started, within this machine's memory.
void check_scene_runs(const std::string& backend, const Scene& scene) {
  const Scene resolved = check_backend(backend, scene).resolved;
  dem::check_over_ranks(resolved, launched_ranks());
  check_run_budget(resolved, backend, physical_memory_bytes());
}

}  // namespace

// The same scene once per seed, then the analysis combined over the seeds from the run files
// (model §5: error bars are the spread over independent initial configurations).
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
  const nlohmann::json header = {
      {"scene", scene.name}, {"backend", options.backend}, {"dimension", D}};
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

void refuse_over_ranks(const std::string& command, const std::string& why) {
  const int ranks = launched_ranks();
  if (ranks <= 1) return;
  // Every rank refuses alike before MPI starts, with nothing to agree on: rank 0 names it.
  if (launched_rank() != 0) throw RefusedElsewhere(2);
  throw InputError("mpirun -n " + std::to_string(ranks),
                   "granjet " + command + " runs as one process: " + why);
}

void refuse_several_ranks(const std::string& command, const std::string& backend) {
  if (backend != "event_driven") return;
  refuse_over_ranks(command,
                    "the event-driven backend handles the collisions one at a time in one global "
                    "order of time, which ranks could share only through a parallel event "
                    "calendar (docs/event_driven.md). Run it without mpirun (run.threads = N "
                    "shares one machine's cores), spread a soft-DEM run with mpirun -n K granjet "
                    "run, or many runs with mpirun -n K granjet campaign");
}

int resume_command(const ResumeOptions& options, std::ostream& out) {
  const std::filesystem::path& partial = options.partial;
  if (partial.extension() != ".partial")
    throw InputError(partial.string(), "is not a run's .partial file (RUN.h5.partial)");
  const analysis::FileSummary stored = analysis::read_summary(partial);
  refuse_several_ranks("resume", stored.backend);
  const MpiSession mpi;  // for mpirun -n K with K > 1: a checkpoint resumes on any K
  const RankTeam ranks = RankTeam::world();
  const bool leader = ranks.rank() == 0;
  Scene scene;
  RunOptions run;
  const std::filesystem::path out_file = std::filesystem::path(partial).replace_extension();
  std::optional<StateArchive> checkpoint;
  const std::optional<int> refused = check_on_every_rank(
      [&] {
        if (!stored.checkpoint)
          throw InputError(partial.string(),
                           "has no checkpoint beside it (" +
                               analysis::checkpoint_path(partial).filename().string() +
                               "): the run stopped before its first run.checkpoint_interval; run "
                               "it again");
        for (const std::string& assignment : options.overrides) {
          const std::string key = assignment.substr(0, assignment.find('='));
          if (std::find(kResumableKeys.begin(), kResumableKeys.end(), key) == kResumableKeys.end())
            throw InputError(key,
                             "cannot change on resume (it would make another run); allowed: "
                             "run.t_end, run.threads, run.progress_interval");
        }
        // The scene as requested: the backend resolves it again, as it did for the run.
        std::istringstream ini(stored.requested_scene_ini.empty() ? stored.scene_ini
                                                                  : stored.requested_scene_ini);
        scene = parse_scene(ini, partial.string() + " (stored scene)", options.overrides);
        if (scene.run.t_end < stored.checkpoint_time)
          throw InputError("run.t_end", std::to_string(scene.run.t_end) +
                                            " lies before the checkpoint at t = " +
                                            std::to_string(stored.checkpoint_time));
        check_scene_runs(stored.backend, scene);
        run.backend = stored.backend;
        run.summary = options.summary;
        run.quiet = options.quiet;
        run.log = options.log;
        run.profile = options.profile;
        run.checkpoint_on_signal = options.checkpoint_on_signal;
        std::vector<OutputPath> outputs = run_outputs(out_file, run.summary);
        std::erase_if(outputs, [&](const OutputPath& o) { return o.path == partial; });
        // Rank 0 writes: the others would find its files.
        if (leader) check_outputs(partial, outputs);
        // Every rank reads it, a checkpoint split over ranks only its shares of the grains;
        // rank 0 writes to it only once the simulator is made, which all ranks make together.
        checkpoint = analysis::read_checkpoint_file(analysis::checkpoint_path(partial),
                                                    {ranks.rank(), ranks.size()});
      },
      std::cerr);
  if (refused) return *refused;
  if (!options.quiet && leader)
    out << "resuming " << out_file.string() << " at t = " << stored.checkpoint_time << "\n";
  return with_dimension(scene.dimension, [&](auto d) {
    return run_scene<d>(scene, run, out_file, out, &*checkpoint);
  });
}

int run_command(const RunOptions& options, std::ostream& out) {
  const MpiSession mpi;  // for mpirun -n K with K > 1
  Scene scene;
  std::filesystem::path out_file = options.out;
  if (out_file.empty()) out_file = options.scene_file.stem().string() + ".h5";
  const std::optional<int> refused = check_on_every_rank(
      [&] {
        if (mpi.active() && !options.seeds.empty())
          throw InputError("--seeds",
                           "runs its seeds one after another on one process; spread seeds "
                           "over ranks with mpirun -n K granjet campaign");
        scene = load_scene(options.scene_file, options.overrides);
        check_scene_runs(options.backend, scene);
        std::vector<OutputPath> outputs = run_outputs(out_file, options.summary);
        for (const std::uint64_t seed : options.seeds)
          for (OutputPath& o :
               run_outputs(member_file(out_file, seed), member_file(options.summary, seed),
                           "seed " + std::to_string(seed) + "'s"))
            outputs.push_back(std::move(o));
        // Rank 0 writes: the others would find its files.
        if (RankTeam::world().rank() == 0) check_outputs(options.scene_file, outputs);
      },
      std::cerr);
  if (refused) return *refused;
  return with_dimension(scene.dimension, [&](auto d) {
    if (!options.seeds.empty()) return run_ensemble<d>(scene, options, out_file, out);
    return run_scene<d>(scene, options, out_file, out, nullptr);
  });
}

}  // namespace granjet
