// The granjet command: run | compare | campaign | info | analyze | --help | --version. Exit codes:
// run/failure_report.hpp.
#include <algorithm>
#include <boost/program_options.hpp>
#include <iostream>
#include <sstream>

#include "app/analyze_command.hpp"
#include "app/campaign_command.hpp"
#include "app/compare_command.hpp"
#include "app/info_command.hpp"
#include "campaign/child_process.hpp"
#include "campaign/mpi_world.hpp"
#include "core/errors.hpp"
#include "run/backend_factory.hpp"
#include "run/failure_report.hpp"
#include "run/run_command.hpp"
#include "run/scene_file.hpp"
#include "run/seed_list.hpp"
#include "run/version.hpp"

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = R"(usage:
  granjet run SCENE.ini [--backend NAME] [--set section.key=value ...] [--out run.h5]
              [--summary run.json] [--seeds 1..10 | 1,4,7] [--author NAME] [--quiet]
              [--no-log] [--profile] [--no-signal-checkpoint]
  granjet resume RUN.h5.partial [--set run.t_end=T] [--summary run.json] [--quiet] [--no-log]
              [--profile] [--no-signal-checkpoint]
  granjet compare SCENE.ini --out DIR [--set section.key=value ...] [--quiet]
  granjet campaign FILE.ini [--out DIR] [--jobs N] [--quick] [--only ID,...] [--dry-run]
              [--status] [--quiet] (mpirun -n K granjet campaign ... spreads it over K ranks)
  granjet info run.h5 [--scene]
  granjet analyze run.h5 [--window t0:t1] [--summary fields.json]
  granjet --help | --version
)";

constexpr const char* kOptions = R"(
run options:
  --backend NAME    soft_dem (default) or event_driven (hard spheres)
  --set KEY=VALUE   override a scene key (repeatable)
  --out FILE        HDF5/H5MD output (default: SCENE's stem + .h5); an .xmf sidecar
                    beside it opens in ParaView (XDMF Reader)
  --summary FILE    JSON summary of the run
  --seeds LIST      an ensemble: one run per seed (A..B or a,b,c) to OUT.seedN.h5; the
                    analysis' mean and spread over the seeds go to OUT and SUMMARY
  --author NAME     the H5MD author (default: $GRANJET_AUTHOR, else the login name)
  --quiet           no progress rows
  --no-log          no OUT's stem + .log (the command, resolved scene, progress rows,
                    warnings and summary, as LAMMPS's log.lammps)
  --profile         the loop's wall time per phase (neighbour rebuilds, contacts, grain
                    update, observers ...) and the share of it that ran serially, at the
                    end and in the summary: why a run does or does not scale with run.threads
  --no-signal-checkpoint  on SIGINT/SIGTERM/SIGHUP keep the last scheduled checkpoint
                    instead of writing one: the resumed run is then bit-identical to one never
                    stopped (campaigns run their runs so)
resume options (a run's .partial goes on from its last checkpoint, run.checkpoint_interval):
  --set KEY=VALUE   only run.t_end (to extend the run), run.threads, run.progress_interval
  --summary FILE    the JSON summary of the whole run (as run --summary)
  --no-log          do not append to the run's .log
  --profile         as for run
  --no-signal-checkpoint  as for run
compare options (every backend on one scene):
  --out DIR         DIR/BACKEND.h5 and DIR/BACKEND.json per backend, and DIR/compare.json
                    with the summaries side by side (also printed as a table)
campaign options (campaign files: see campaigns/thesis.ini and docs/campaigns.md):
  --out DIR         where the runs go (default out/<FILE's stem>, with --quick
                    out/<FILE's stem>-quick): DIR/GROUP/POINT.seedN.h5
                    (+ .json summary, .ini resolved scene, .log), the ensembles
                    DIR/GROUP/POINT.h5 (+ .json), and DIR/manifest.json; a run whose complete
                    output is there (same resolved scene) is not run again
  --jobs N          runs at a time on this machine (default: the cores it may use; under
                    mpirun 1 per rank)
  --quick           one seed per group, run.t_end and the analysis window shortened by the
                    campaign's quick_fraction (for tests)
  --only IDS        only the groups serving these result ids (e.g. F5.3,T5.1)
  --dry-run         list the runs and their estimated cost; run nothing
  --status          where DIR stands: running or not, runs by status, the time still to run,
                    the failures with their logs; reads the manifest only
  --quiet           no row per finished run
info options:
  --scene           print only the stored scene (a scene file that redoes the run)
analyze options (measurements of the stored frames; contact stress needs inline analysis):
  --window T0:T1    time-average window (default: the scene's analysis.window_*)
  --summary FILE    JSON of the fields and global measurements
)";

void print_help() {
  std::cout << "granjet " << granjet::kVersion
            << ": granular jets on a soft-sphere DEM and an event-driven backend\n\n"
            << kUsage << kOptions
            << "\nscene keys (INI sections [scene], [contact], ... in the scene file):\n"
            << granjet::scene_keys_help();
}

// `granjet COMMAND --help`: the command's usage lines and options, cut from the whole help;
// for run, resume and compare the scene keys too.
void print_command_help(const std::string& command) {
  std::istringstream usage(kUsage), options(kOptions);
  std::cout << "usage:\n";
  bool in_usage = false;
  for (std::string line; std::getline(usage, line);) {
    if (line.starts_with("  granjet ")) in_usage = line.starts_with("  granjet " + command + " ");
    if (in_usage) std::cout << line << "\n";
  }
  bool in_block = false;
  for (std::string line; std::getline(options, line);) {
    if (!line.starts_with(" ")) in_block = line.starts_with(command + " options");
    if (in_block) std::cout << line << "\n";
  }
  if (command == "run" || command == "resume" || command == "compare")
    std::cout << "\nscene keys (INI sections [scene], [contact], ... in the scene file):\n"
              << granjet::scene_keys_help();
}

bool asks_for_help(const std::vector<std::string>& args) {
  return std::find(args.begin(), args.end(), "--help") != args.end() ||
         std::find(args.begin(), args.end(), "-h") != args.end();
}

// Parses a subcommand's arguments; `positional` names its one positional argument.
po::variables_map parse(const std::vector<std::string>& args, const po::options_description& desc,
                        const char* positional) {
  po::positional_options_description pos;
  pos.add(positional, 1);
  po::variables_map vm;
  po::store(po::command_line_parser(args).options(desc).positional(pos).run(), vm);
  po::notify(vm);
  return vm;
}

int run(const std::vector<std::string>& args) {
  granjet::RunOptions o;
  po::options_description desc;
  desc.add_options()("scene", po::value<std::string>()->required())(
      "backend", po::value(&o.backend))("set", po::value(&o.overrides)->composing())(
      "out", po::value<std::string>())("summary", po::value<std::string>())(
      "seeds", po::value<std::string>())("quiet", po::bool_switch(&o.quiet))(
      "no-log", po::bool_switch())("author", po::value(&o.author))(
      "profile", po::bool_switch(&o.profile))("no-signal-checkpoint", po::bool_switch());
  const po::variables_map vm = parse(args, desc, "scene");
  o.scene_file = vm["scene"].as<std::string>();
  o.log = !vm["no-log"].as<bool>();
  o.checkpoint_on_signal = !vm["no-signal-checkpoint"].as<bool>();
  if (vm.count("seeds")) o.seeds = granjet::parse_seeds(vm["seeds"].as<std::string>(), "--seeds");
  if (vm.count("out")) o.out = vm["out"].as<std::string>();
  if (vm.count("summary")) o.summary = vm["summary"].as<std::string>();
  granjet::refuse_several_ranks("run", o.backend);
  return granjet::run_command(o, std::cout);
}

int resume(const std::vector<std::string>& args) {
  granjet::ResumeOptions o;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())(
      "set", po::value(&o.overrides)->composing())("summary", po::value<std::string>())(
      "quiet", po::bool_switch(&o.quiet))("no-log", po::bool_switch())(
      "profile", po::bool_switch(&o.profile))("no-signal-checkpoint", po::bool_switch());
  const po::variables_map vm = parse(args, desc, "file");
  o.partial = vm["file"].as<std::string>();
  o.log = !vm["no-log"].as<bool>();
  o.checkpoint_on_signal = !vm["no-signal-checkpoint"].as<bool>();
  if (vm.count("summary")) o.summary = vm["summary"].as<std::string>();
  return granjet::resume_command(o, std::cout);
}

int analyze(const std::vector<std::string>& args) {
  granjet::AnalyzeOptions o;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())(
      "window", po::value<std::string>())("summary", po::value<std::string>());
  const po::variables_map vm = parse(args, desc, "file");
  granjet::refuse_over_ranks("analyze",
                             "it reads a run's frames and writes their fields into the run's "
                             "file, which one process writes. Run it without mpirun");
  o.file = vm["file"].as<std::string>();
  if (vm.count("summary")) o.summary = vm["summary"].as<std::string>();
  if (vm.count("window")) {
    const std::string w = vm["window"].as<std::string>();
    const auto colon = w.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument(w);
      o.window = {std::stod(w.substr(0, colon)), std::stod(w.substr(colon + 1))};
    } catch (const std::logic_error&) {
      throw granjet::InputError("--window", "'" + w + "' is not t0:t1");
    }
  }
  return granjet::analyze_command(o, std::cout);
}

int compare(const std::vector<std::string>& args) {
  granjet::CompareOptions o;
  po::options_description desc;
  desc.add_options()("scene", po::value<std::string>()->required())(
      "out", po::value<std::string>()->required())("set", po::value(&o.overrides)->composing())(
      "quiet", po::bool_switch(&o.quiet));
  const po::variables_map vm = parse(args, desc, "scene");
  o.scene_file = vm["scene"].as<std::string>();
  o.out_dir = vm["out"].as<std::string>();
  granjet::refuse_several_ranks("compare", "event_driven");
  return granjet::compare_command(o, std::cout);
}

int campaign(const std::vector<std::string>& args, const std::vector<std::string>& all) {
  granjet::CampaignOptions o;
  std::string only;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())("out", po::value<std::string>())(
      "jobs", po::value(&o.jobs))("quick", po::bool_switch(&o.quick))("only", po::value(&only))(
      "dry-run", po::bool_switch(&o.dry_run))("status", po::bool_switch(&o.status))(
      "quiet", po::bool_switch(&o.quiet));
  const po::variables_map vm = parse(args, desc, "file");
  o.file = vm["file"].as<std::string>();
  if (vm.count("out")) o.out_dir = vm["out"].as<std::string>();
  for (std::size_t start = 0; !only.empty() && start <= only.size();) {
    const std::size_t comma = std::min(only.find(',', start), only.size());
    if (comma > start) o.only.push_back(only.substr(start, comma - start));
    start = comma + 1;
  }
  o.command_line = all;
  return granjet::campaign_command(o, std::cout);
}

int info(const std::vector<std::string>& args) {
  bool scene_only = false;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())("scene",
                                                                   po::bool_switch(&scene_only));
  const po::variables_map vm = parse(args, desc, "file");
  granjet::refuse_over_ranks("info",
                             "it reads a run's file and prints what it holds. Run it "
                             "without mpirun");
  return granjet::info_command({vm["file"].as<std::string>(), scene_only}, std::cout);
}

}  // namespace

int main(int argc, char** argv) {
  granjet::end_with_parent();
  const std::vector<std::string> all(argv + 1, argv + argc);
  if (all.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  const std::string& command = all.front();
  const std::vector<std::string> args(all.begin() + 1, all.end());
  try {
    if (command == "--help" || command == "-h" || command == "help") {
      print_help();
      return 0;
    }
    if (command == "--version") {
      std::cout << "granjet " << granjet::kVersion << " (commit " << granjet::kCommit << ")\n";
      return 0;
    }
    const std::vector<std::string> commands = {"run",  "resume",   "compare",
                                               "info", "campaign", "analyze"};
    if (std::find(commands.begin(), commands.end(), command) != commands.end() &&
        asks_for_help(args)) {
      print_command_help(command);
      return 0;
    }
    if (command == "run") return run(args);
    if (command == "resume") return resume(args);
    if (command == "compare") return compare(args);
    if (command == "info") return info(args);
    if (command == "campaign") return campaign(args, all);
    if (command == "analyze") return analyze(args);
    std::cerr << "granjet: unknown command '" << command << "'\n" << kUsage;
    return 2;
  } catch (const po::error& e) {
    std::cerr << "granjet " << command << ": " << e.what() << "\n" << kUsage;
    return 2;
  } catch (...) {
    return granjet::report_current_exception(std::cerr);
  }
}
