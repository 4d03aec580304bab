#include "campaign/campaign_runner.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <deque>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "analysis/h5md_reader.hpp"
#include "campaign/campaign_manifest.hpp"
#include "core/number_text.hpp"
#include "run/backend_factory.hpp"
#include "run/ensemble_output.hpp"
#include "run/interrupts.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

constexpr auto kPoll = std::chrono::milliseconds(20);
constexpr int kDiskFull = 4;  // granjet's exit code (run/failure_report.hpp)

std::optional<nlohmann::json> read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

// Whether `file` is a granjet output of this run's backend and resolved scene. The stored
// scene is resolved again, by the current parser, so a key added since (whose default keeps
// the old behaviour) does not make finished runs look foreign, and by the backend, since files
// written before it declared its adaptations store the scene as requested.
bool holds_run(const std::filesystem::path& file, const PlannedRun& run) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  try {
    const analysis::FileSummary s = analysis::read_summary(file);
    std::istringstream stored(s.scene_ini);
    const Scene scene = check_backend(s.backend, parse_scene(stored, file.string(), {})).resolved;
    return scene_hash(s.backend, scene_to_ini(scene)) == run.hash;
  } catch (const std::exception&) {
    return false;  // unreadable, or a scene this build cannot parse: not this run's output
  }
}

// Whether the run's .partial holds a checkpoint of this very run: a run interrupted (or killed)
// after it goes on from there.
bool resumable(const PlannedRun& run) {
  if (!holds_run(run.file(".h5.partial"), run)) return false;
  try {
    return analysis::read_summary(run.file(".h5.partial")).checkpoint;
  } catch (const std::exception&) {
    return false;
  }
}

// The last line a run's log holds: the error of a run that failed.
std::string last_line(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string last;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) last = line;
  return last;
}

RunState state_of_exit(int code) {
  if (code == 128 + SIGINT || code == 128 + SIGTERM || code == 128 + SIGHUP)
    return RunState::kInterrupted;
  return code == 0 ? RunState::kComplete : code == 3 ? RunState::kBlownUp : RunState::kFailed;
}

class Coordinator {
 public:
  Coordinator(const CampaignFile& campaign, const CampaignPlan& plan, MpiWorld& world,
              const RunnerOptions& options, std::ostream& out)
      : campaign_(campaign),
        plan_(plan),
        world_(world),
        options_(options),
        out_(out),
        outcomes_(plan.runs.size()),
        ensemble_of_(plan.runs.size()),
        manifest_(options.out_dir),
        hosts_(world.hostnames()) {
    for (std::size_t e = 0; e < plan.ensembles.size(); ++e)
      for (std::size_t r : plan.ensembles[e].runs) ensemble_of_[r] = e;
  }

  int run() {
    start_ = std::chrono::steady_clock::now();
    begin_invocation();
    find_complete_runs();
    for (std::size_t e = 0; e < plan_.ensembles.size(); ++e) merge_if_settled(e);
    std::vector<std::optional<std::pair<std::size_t, ChildProcess>>> slots(options_.jobs);
    int workers = world_.size() - 1;  // ranks not yet told to stop
    const Interrupts interrupts;
    while (!queue_.empty() || workers > 0 ||
           std::any_of(slots.begin(), slots.end(), [](const auto& s) { return s.has_value(); })) {
      bool busy = false;
      // A signal: no run starts any more, and the running ones stop (once) at their last
      // scheduled checkpoint, from which the next invocation resumes them.
      if (interrupts.signal() != 0 && !interrupted_) {
        interrupted_ = interrupts.signal();
        queue_.clear();
        for (auto& slot : slots)
          if (slot) slot->second.signal(interrupted_);
      }
      for (auto& slot : slots) {
        if (slot) {
          if (const auto code = slot->second.poll()) {
            finished(slot->first, *code, slot->second.seconds(), 0);
            slot.reset();
            busy = true;
          }
        }
        if (!slot && !queue_.empty()) {
          const std::size_t r = next();
          mark_running(r, 0);
          slot.emplace(r, start_run(plan_.runs[r]));
        }
      }
      while (const auto report = world_.try_receive()) {
        busy = true;
        if (report->run >= 0)
          finished(static_cast<std::size_t>(report->run), report->exit_code, report->seconds,
                   report->rank);
        if (queue_.empty()) {
          world_.assign(report->rank, -1);
          --workers;
        } else {
          const std::size_t r = next();
          mark_running(r, report->rank);
          world_.assign(report->rank, static_cast<std::int64_t>(r));
        }
      }
      if (!busy) std::this_thread::sleep_for(kPoll);
    }
    return end_invocation();
  }

 private:
  void begin_invocation() {
    nlohmann::json& m = manifest_.json();
    m["campaign"] = campaign_.name;
    m["file"] = std::filesystem::absolute(campaign_.file).string();
    m["description"] = campaign_.description;
    nlohmann::json inv = options_.invocation;
    inv["started"] = utc_now();
    inv["host"] = hosts_.front();
    inv["jobs"] = options_.jobs;
    inv["ranks"] = world_.size();
    inv["planned"] = plan_.runs.size();
    m["invocations"].push_back(inv);
  }

  // Runs whose complete output is already there are not run again; the rest queue up, the
  // longest first (fewest idle slots at the end).
  void find_complete_runs() {
    std::vector<std::size_t> pending;
    for (std::size_t r = 0; r < plan_.runs.size(); ++r) {
      const PlannedRun& run = plan_.runs[r];
      outcomes_[r].state = stored_state(run);
      nlohmann::json& entry = manifest_.run(run.name);
      // An entry of an earlier invocation keeps its history (host, times) if it describes this
      // very run: the same hash, or a complete file that holds this run under a scene hash
      // written before keys were added (stored_state resolves it anew); its paths follow DIR,
      // which may have moved.
      const bool known = entry.is_object() && (entry.value("hash", std::string()) == run.hash ||
                                               outcomes_[r].state == RunState::kComplete);
      if (!known) entry = nlohmann::json::object();
      entry.update(describe(run));
      if (outcomes_[r].state == RunState::kMissing) {
        entry["status"] = "pending";
        pending.push_back(r);
      } else {
        entry["status"] = state_name(outcomes_[r].state);
        outcomes_[r].seconds = entry.value("wall_seconds", 0.0);
        ++found_;
      }
    }
    std::stable_sort(pending.begin(), pending.end(), [&](std::size_t a, std::size_t b) {
      return plan_.runs[a].cost.seconds > plan_.runs[b].cost.seconds;
    });
    queue_.assign(pending.begin(), pending.end());
    for (std::size_t r : pending) to_do_seconds_ += plan_.runs[r].cost.seconds;
    manifest_.invocation()["found_complete"] = found_;
    manifest_.save();
    if (!options_.quiet)
      out_ << "campaign " << campaign_.name << ": " << plan_.runs.size() << " runs, " << found_
           << " already done, " << pending.size() << " to run on " << options_.jobs
           << " local slot(s) and " << world_.size() - 1 << " other rank(s)\n"
           << std::flush;
  }

  nlohmann::json describe(const PlannedRun& run) const {
    const CampaignGroup& g = campaign_.groups[run.group];
    return {{"group", g.name},
            {"point", run.point},
            {"seed", run.seed},
            {"backend", run.backend},
            {"results", g.results},
            {"hash", run.hash},
            {"overrides", run.overrides},
            {"output", run.file(".h5").string()},
            {"summary", run.file(".json").string()},
            {"log", run.file(".log").string()},
            {"cost",
             {{"grains", run.cost.grains},
              {"steps", run.cost.steps},
              {"particle_steps", run.cost.particle_steps},
              {"grain_time", run.cost.grain_time},
              {"estimated_seconds", run.cost.seconds}}}};
  }

  std::size_t next() {
    const std::size_t r = queue_.front();
    queue_.pop_front();
    return r;
  }

  void mark_running(std::size_t r, int rank) {
    nlohmann::json& entry = manifest_.run(plan_.runs[r].name);
    entry = describe(plan_.runs[r]);
    entry["status"] = "running";
    entry["host"] = hosts_.at(rank);
    entry["rank"] = rank;
    entry["started"] = utc_now();
    manifest_.save();
    if (resumable(plan_.runs[r]))  // as start_run sees it, here or on a worker rank
      resuming_.insert(r);
    else
      resuming_.erase(r);
  }

  void finished(std::size_t r, int code, double seconds, int rank) {
    // A full disk stops the campaign starting runs: each would fail the same way.
    if (code == kDiskFull && !queue_.empty()) {
      queue_.clear();
      out_ << "no space left on the disk (" << plan_.runs[r].name
           << "): no more runs are started; free space and run the same command\n"
           << std::flush;
    }
    // A run killed from outside (kill -9, the kernel's out-of-memory killer) goes back to the
    // queue once and resumes from its checkpoint; a second kill is its failure.
    if (code == 128 + SIGKILL && interrupted_ == 0 && !requeued_.contains(r)) {
      requeued_.insert(r);
      queue_.push_front(r);
      manifest_.run(plan_.runs[r].name)["status"] = "pending";
      manifest_.save();
      if (!options_.quiet)
        out_ << plan_.runs[r].name << "  killed (exit code " << code
             << "): back in the queue, to resume from its checkpoint\n"
             << std::flush;
      return;
    }
    // A resume that fails on its file (exit 1: the .partial could not be read back or written
    // on, as a kill in the middle of HDF5's writes can leave it) would fail at every invocation:
    // the run starts again from t = 0, once.
    if (code == 1 && resuming_.contains(r) && interrupted_ == 0 && !restarted_.contains(r)) {
      restarted_.insert(r);
      const PlannedRun& run = plan_.runs[r];
      out_ << run.name << "  could not be resumed (" << last_line(run.file(".log"))
           << "): its .partial and checkpoint are discarded and it starts again from t = 0\n"
           << std::flush;
      for (const char* stale : {".h5.partial", ".h5.checkpoint"})
        std::filesystem::remove(run.file(stale));
      queue_.push_front(r);
      manifest_.run(run.name)["status"] = "pending";
      manifest_.save();
      return;
    }
    RunOutcome& o = outcomes_[r];
    o.state = state_of_exit(code);
    o.executed = true;
    o.seconds = seconds;
    nlohmann::json& entry = manifest_.run(plan_.runs[r].name);
    entry["status"] = state_name(o.state);
    entry["exit_code"] = code;
    entry["wall_seconds"] = seconds;
    entry["host"] = hosts_.at(rank);
    entry["rank"] = rank;
    entry["finished"] = utc_now();
    done_seconds_ += plan_.runs[r].cost.seconds;
    ++executed_;
    manifest_.save();
    if (!options_.quiet) print_progress(r, rank, code);
    merge_if_settled(ensemble_of_[r]);
  }

  void print_progress(std::size_t r, int rank, int code) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta =
        done_seconds_ > 0.0 ? elapsed * (to_do_seconds_ - done_seconds_) / done_seconds_ : 0.0;
    char line[64];
    std::snprintf(line, sizeof line, "[%zu/%zu] ", executed_, plan_.runs.size() - found_);
    out_ << line << plan_.runs[r].name << "  " << state_name(outcomes_[r].state);
    if (outcomes_[r].state != RunState::kComplete)
      out_ << " (exit code " << code << ", see " << plan_.runs[r].file(".log").string() << ")";
    std::snprintf(line, sizeof line, "  %.1f s", outcomes_[r].seconds);
    out_ << line << (world_.size() > 1 ? "  rank " + std::to_string(rank) : "") << "  ETA "
         << format_duration(eta) << "\n"
         << std::flush;
  }

  // Merges an ensemble once none of its seeds is still to run, unless an identical merge is on
  // disk already (same member hashes, nothing rerun since).
  void merge_if_settled(std::size_t e) {
    const PlannedEnsemble& ens = plan_.ensembles[e];
    if (!ens.analysed) return;
    nlohmann::json hashes = nlohmann::json::array();
    bool any_executed = false;
    for (std::size_t r : ens.runs) {
      if (outcomes_[r].state == RunState::kMissing) return;
      hashes.push_back(plan_.runs[r].hash);
      any_executed |= outcomes_[r].executed;
    }
    nlohmann::json& entry = manifest_.ensemble(ens.name);
    if (!any_executed && entry.is_object() && entry.value("hashes", nlohmann::json()) == hashes &&
        std::filesystem::exists(ens.file(".json")))
      return;
    std::vector<EnsembleMember> members;
    for (std::size_t r : ens.runs)
      if (outcomes_[r].state == RunState::kComplete)
        members.push_back({plan_.runs[r].seed, plan_.runs[r].file(".h5")});
    const PlannedRun& first = plan_.runs[ens.runs.front()];
    const nlohmann::json header = {{"scene", first.scene.name},
                                   {"backend", first.backend},
                                   {"dimension", first.scene.dimension}};
    const int combined =
        merge_ensemble(ens.file(".h5"), ens.file(".json"), header, members, first.scene.dimension);
    if (combined == 0) std::filesystem::remove(ens.file(".json"));
    entry = {{"group", campaign_.groups[ens.group].name},
             {"point", ens.point},
             {"seeds", ens.runs.size()},
             {"hashes", hashes},
             {"combined", combined},
             {"output", ens.file(".h5").string()},
             {"summary", ens.file(".json").string()},
             {"merged", utc_now()}};
    manifest_.save();
    if (!options_.quiet)
      out_ << "ensemble " << ens.name << ": " << combined << " of " << ens.runs.size()
           << " seeds combined into " << ens.file(".h5").string() << "\n"
           << std::flush;
  }

  int end_invocation() {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::size_t complete = 0, blown_up = 0, failed = 0;
    for (const RunOutcome& o : outcomes_) {
      complete += o.state == RunState::kComplete;
      blown_up += o.state == RunState::kBlownUp;
      failed += o.state == RunState::kFailed;
    }
    nlohmann::json& inv = manifest_.invocation();
    inv["finished"] = utc_now();
    inv["executed"] = executed_;
    inv["complete"] = complete;
    inv["blown_up"] = blown_up;
    inv["failed"] = failed;
    inv["wall_seconds"] = wall;
    manifest_.save();
    print_outcome_table(plan_, outcomes_, wall, out_);
    if (interrupted_ != 0) {
      out_ << "interrupted (signal " << interrupted_ << "): `granjet campaign` again resumes "
           << "the interrupted runs from their checkpoints\n";
      return 128 + interrupted_;
    }
    return failed > 0 ? 1 : blown_up > 0 ? 3 : 0;
  }

  const CampaignFile& campaign_;
  const CampaignPlan& plan_;
  MpiWorld& world_;
  const RunnerOptions& options_;
  std::ostream& out_;
  std::vector<RunOutcome> outcomes_;
  std::vector<std::size_t> ensemble_of_;
  CampaignManifest manifest_;
  std::vector<std::string> hosts_;
  std::deque<std::size_t> queue_;
  std::chrono::steady_clock::time_point start_;
  std::size_t found_ = 0, executed_ = 0;
  double to_do_seconds_ = 0.0, done_seconds_ = 0.0;
  int interrupted_ = 0;              // the signal that stopped this invocation
  std::set<std::size_t> requeued_;   // runs killed once and queued again
  std::set<std::size_t> resuming_;   // runs started from their checkpoints
  std::set<std::size_t> restarted_;  // runs whose resume failed, started again
};

}  // namespace

RunState stored_state(const PlannedRun& run) {
  const std::optional<nlohmann::json> summary = read_json(run.file(".json"));
  if (!summary || !summary->is_object()) return RunState::kMissing;
  const std::string status = summary->value("status", std::string());
  if (status == "complete" && holds_run(run.file(".h5"), run)) return RunState::kComplete;
  if (status.rfind("blow-up", 0) == 0 && holds_run(run.file(".h5.partial"), run))
    return RunState::kBlownUp;
  return RunState::kMissing;
}

namespace {

// "section.key" -> value of a scene's INI text (scene_to_ini's layout).
std::map<std::string, std::string> ini_values(const std::string& ini) {
  std::map<std::string, std::string> values;
  std::istringstream in(ini);
  std::string section;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line.front() == '[' && line.back() == ']') {
      section = line.substr(1, line.size() - 2);
      continue;
    }
    const std::size_t eq = line.find(" = ");
    if (eq != std::string::npos) values[section + "." + line.substr(0, eq)] = line.substr(eq + 3);
  }
  return values;
}

// A value as messages show it: numbers with six digits (the INI keeps 17 to round-trip).
std::string shown(const std::string& value) {
  try {
    std::size_t used = 0;
    const double number = std::stod(value, &used);
    if (used == value.size()) return number_text(number);
  } catch (const std::logic_error&) {
  }
  return value;
}

// The keys whose values differ, "KEY A -> B", at most three and how many more.
std::string changed_keys(const std::string& stored, const std::string& planned) {
  const std::map<std::string, std::string> a = ini_values(stored), b = ini_values(planned);
  std::vector<std::string> changes;
  for (const auto& [key, value] : b) {
    const auto it = a.find(key);
    const std::string old_value = it == a.end() ? "(none)" : it->second;
    if (old_value != value) changes.push_back(key + " " + shown(old_value) + " -> " + shown(value));
  }
  for (const auto& [key, value] : a)
    if (!b.contains(key)) changes.push_back(key + " " + shown(value) + " -> (none)");
  std::string text;
  for (std::size_t k = 0; k < changes.size() && k < 3; ++k)
    text += (k > 0 ? ", " : "") + changes[k];
  if (changes.size() > 3) text += " and " + std::to_string(changes.size() - 3) + " more";
  return text.empty() ? "the backend" : text;
}

}  // namespace

std::string why_it_runs(const PlannedRun& run) {
  const RunState state = stored_state(run);
  if (state == RunState::kComplete || state == RunState::kBlownUp) return "";
  if (resumable(run))
    return "resumes from its checkpoint at t = " +
           std::to_string(analysis::read_summary(run.file(".h5.partial")).checkpoint_time);
  for (const char* kept : {".h5", ".h5.partial"}) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(run.file(kept), ec)) continue;
    try {
      const analysis::FileSummary s = analysis::read_summary(run.file(kept));
      std::istringstream stored(s.scene_ini);
      const Scene scene =
          check_backend(s.backend, parse_scene(stored, run.file(kept).string(), {})).resolved;
      if (scene_hash(s.backend, scene_to_ini(scene)) != run.hash)
        return "its file holds another scene: " + changed_keys(scene_to_ini(scene), run.scene_ini);
      return "stopped before its end (status " + s.status + ")";
    } catch (const std::exception& e) {
      return std::string("its file cannot be read (") + e.what() + ")";
    }
  }
  return "not run yet";
}

ChildProcess start_run(const PlannedRun& run) {
  std::filesystem::create_directories(run.base.parent_path());
  // Signals leave the last scheduled checkpoint, so a resumed run is bit-identical to a run
  // never stopped.
  if (resumable(run))
    return ChildProcess({"resume", run.file(".h5.partial").string(), "--summary",
                         run.file(".json").string(), "--no-log", "--no-signal-checkpoint"},
                        run.file(".log"));
  for (const char* stale : {".h5", ".h5.partial", ".h5.checkpoint", ".json", ".xmf", ".fields.xmf"})
    std::filesystem::remove(run.file(stale));
  {
    std::ofstream ini(run.file(".ini"));
    ini << "# " << run.name << ": the resolved scene of this campaign run\n";
    for (const std::string& adaptation : run.adaptations) ini << "# " << adaptation << "\n";
    ini << run.scene_ini;
    if (!ini.flush()) throw std::runtime_error("cannot write " + run.file(".ini").string());
  }
  std::ofstream(run.file(".log"), std::ios::trunc);
  // The child's stdout and stderr are its log: its own would be the same rows (the resolved
  // scene and the summary are the .ini and the .json).
  return ChildProcess({"run", run.file(".ini").string(), "--backend", run.backend, "--out",
                       run.file(".h5").string(), "--summary", run.file(".json").string(),
                       "--no-log", "--no-signal-checkpoint"},
                      run.file(".log"));
}

int coordinate_campaign(const CampaignFile& campaign, const CampaignPlan& plan, MpiWorld& world,
                        const RunnerOptions& options, std::ostream& out) {
  return Coordinator(campaign, plan, world, options, out).run();
}

void work_for_campaign(const CampaignPlan& plan, MpiWorld& world) {
  world.hostnames();  // the collective call rank 0 makes in its coordinator
  MpiWorld::Report report;
  const Interrupts interrupts;  // passed on to the run, which stops at its last checkpoint
  for (std::int64_t r; (r = world.report_and_receive(report)) >= 0;) {
    ChildProcess child = start_run(plan.runs.at(static_cast<std::size_t>(r)));
    bool passed_on = false;
    std::optional<int> code;
    while (!(code = child.poll())) {
      if (interrupts.signal() != 0 && !passed_on) {
        child.signal(interrupts.signal());
        passed_on = true;
      }
      std::this_thread::sleep_for(kPoll);
    }
    report.run = r;
    report.exit_code = *code;
    report.seconds = child.seconds();
  }
}

}  // namespace granjet
