// The granjet command: run | compare | info | --help | --version. Exit codes: 0 done, 1 failure
// (I/O and other errors), 2 bad input, 3 numerical blow-up (output kept as .partial).
#include <boost/program_options.hpp>
#include <charconv>
#include <iostream>

#include "analysis/h5md_reader.hpp"
#include "app/analyze_command.hpp"
#include "app/backend_factory.hpp"
#include "app/compare_command.hpp"
#include "app/run_command.hpp"
#include "app/scene_file.hpp"
#include "app/version.hpp"
#include "core/errors.hpp"

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage = R"(usage:
  granjet run SCENE.ini [--backend NAME] [--set section.key=value ...] [--out run.h5]
              [--summary run.json] [--seeds 1..10 | 1,4,7] [--quiet]
  granjet compare SCENE.ini --out DIR [--set section.key=value ...] [--quiet]
  granjet info run.h5 [--scene]
  granjet analyze run.h5 [--window t0:t1] [--summary fields.json]
  granjet --help | --version
)";

void print_help() {
  std::cout << "granjet " << granjet::kVersion
            << ": granular jets on a soft-sphere DEM and an event-driven backend\n\n"
            << kUsage << R"(
run options:
  --backend NAME    soft_dem (default) or event_driven (hard spheres)
  --set KEY=VALUE   override a scene key (repeatable)
  --out FILE        HDF5/H5MD output (default: SCENE's stem + .h5); an .xmf sidecar
                    beside it opens in ParaView (XDMF Reader)
  --summary FILE    JSON summary of the run
  --seeds LIST      an ensemble: one run per seed (A..B or a,b,c) to OUT.seedN.h5; the
                    analysis' mean and spread over the seeds go to OUT and SUMMARY
  --quiet           no progress rows
compare options (every backend on one scene):
  --out DIR         DIR/BACKEND.h5 and DIR/BACKEND.json per backend, and DIR/compare.json
                    with the summaries side by side (also printed as a table)
info options:
  --scene           print only the stored scene (a scene file that redoes the run)
analyze options (measurements of the stored frames; contact stress needs inline analysis):
  --window T0:T1    time-average window (default: the scene's analysis.window_*)
  --summary FILE    JSON of the fields and global measurements

scene keys (INI sections [scene], [contact], ... in the scene file):
)" << granjet::scene_keys_help();
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

// "1..10" (inclusive) or "3,7,9".
std::vector<std::uint64_t> parse_seeds(const std::string& text) {
  const auto bad = [&] {
    return granjet::InputError("--seeds", "'" + text +
                                              "' is not a range A..B (A <= B) or a list a,b,c");
  };
  const auto number = [&](const std::string& s) {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || s.empty()) throw bad();
    return v;
  };
  std::vector<std::uint64_t> seeds;
  if (const auto dots = text.find(".."); dots != std::string::npos) {
    const std::uint64_t first = number(text.substr(0, dots)), last = number(text.substr(dots + 2));
    if (last < first || last - first > 10000) throw bad();
    for (std::uint64_t s = first; s <= last; ++s) seeds.push_back(s);
    return seeds;
  }
  std::size_t start = 0;
  for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    seeds.push_back(number(text.substr(start, comma - start)));
  seeds.push_back(number(text.substr(start)));
  return seeds;
}

int run(const std::vector<std::string>& args) {
  granjet::RunOptions o;
  po::options_description desc;
  desc.add_options()("scene", po::value<std::string>()->required())(
      "backend", po::value(&o.backend))("set", po::value(&o.overrides)->composing())(
      "out", po::value<std::string>())("summary", po::value<std::string>())(
      "seeds", po::value<std::string>())("quiet", po::bool_switch(&o.quiet));
  const po::variables_map vm = parse(args, desc, "scene");
  o.scene_file = vm["scene"].as<std::string>();
  if (vm.count("seeds")) o.seeds = parse_seeds(vm["seeds"].as<std::string>());
  if (vm.count("out")) o.out = vm["out"].as<std::string>();
  if (vm.count("summary")) o.summary = vm["summary"].as<std::string>();
  return granjet::run_command(o, std::cout);
}

int analyze(const std::vector<std::string>& args) {
  granjet::AnalyzeOptions o;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())(
      "window", po::value<std::string>())("summary", po::value<std::string>());
  const po::variables_map vm = parse(args, desc, "file");
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
  return granjet::compare_command(o, std::cout);
}

int info(const std::vector<std::string>& args) {
  bool scene_only = false;
  po::options_description desc;
  desc.add_options()("file", po::value<std::string>()->required())("scene",
                                                                   po::bool_switch(&scene_only));
  const po::variables_map vm = parse(args, desc, "file");
  const auto summary = granjet::analysis::read_summary(vm["file"].as<std::string>());
  if (scene_only)
    std::cout << summary.scene_ini;
  else
    granjet::analysis::print_summary(summary, std::cout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
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
    if (command == "run") return run(args);
    if (command == "compare") return compare(args);
    if (command == "info") return info(args);
    if (command == "analyze") return analyze(args);
    std::cerr << "granjet: unknown command '" << command << "'\n" << kUsage;
    return 2;
  } catch (const granjet::InputError& e) {
    std::cerr << "granjet: " << e.what() << "\n";
    return 2;
  } catch (const po::error& e) {
    std::cerr << "granjet " << command << ": " << e.what() << "\n" << kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "granjet: " << e.what() << "\n";
    return 1;
  }
}
