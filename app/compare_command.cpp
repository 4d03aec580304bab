#include "app/compare_command.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>

#include "run/run_command.hpp"
#include "run/backend_factory.hpp"
#include "run/run_budget.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

// The rows of the side-by-side table: summary keys (a/b for nested ones) in this order, then
// every measured quantity either backend reports.
const std::vector<std::string> kRows = {"status",
                                        "grains",
                                        "removed",
                                        "wall_seconds",
                                        "cpu_seconds",
                                        "particle_steps_per_second",
                                        "collisions_per_second",
                                        "energy/kinetic",
                                        "energy/dissipated",
                                        "energy/removed"};

const nlohmann::json* find(const nlohmann::json& summary, const std::string& row) {
  const nlohmann::json* node = &summary;
  std::size_t begin = 0;
  while (begin <= row.size()) {
    const std::size_t slash = std::min(row.find('/', begin), row.size());
    const std::string key = row.substr(begin, slash - begin);
    if (!node->is_object() || !node->contains(key)) return nullptr;
    node = &(*node)[key];
    begin = slash + 1;
  }
  return node;
}

std::string cell(const nlohmann::json* value) {
  if (value == nullptr) return "-";
  if (value->is_string()) return value->get<std::string>().substr(0, 22);
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value->get<double>());
  return text;
}

}  // namespace

int compare_command(const CompareOptions& options, std::ostream& out) {
  const Scene scene = load_scene(options.scene_file, options.overrides);
  const std::vector<std::string> backends = backend_names();
  for (const std::string& backend : backends) {
    check_run_budget(check_backend(backend, scene).resolved, backend, physical_memory_bytes());
  }
  std::filesystem::create_directories(options.out_dir);

  int code = 0;
  nlohmann::json summaries;
  for (const std::string& backend : backends) {
    RunOptions run;
    run.scene_file = options.scene_file;
    run.backend = backend;
    run.overrides = options.overrides;
    run.out = options.out_dir / (backend + ".h5");
    run.summary = options.out_dir / (backend + ".json");
    run.quiet = options.quiet;
    if (!options.quiet) out << "== " << backend << "\n";
    code = std::max(code, run_command(run, out));
    std::ifstream in(run.summary);
    summaries[backend] = nlohmann::json::parse(in);
  }

  std::vector<std::string> rows = kRows;
  for (const std::string& backend : backends)
    if (summaries[backend].contains("measured"))
      for (const auto& [key, value] : summaries[backend]["measured"].items())
        if (std::find(rows.begin(), rows.end(), "measured/" + key) == rows.end())
          rows.push_back("measured/" + key);
  nlohmann::json side_by_side = nlohmann::json::object();
  char line[160];
  std::snprintf(line, sizeof line, "%-28s", "");
  out << line;
  for (const std::string& backend : backends) {
    std::snprintf(line, sizeof line, " %22s", backend.c_str());
    out << line;
  }
  out << "\n";
  for (const std::string& row : rows) {
    std::snprintf(line, sizeof line, "%-28s", row.c_str());
    out << line;
    for (const std::string& backend : backends) {
      const nlohmann::json* value = find(summaries[backend], row);
      side_by_side[row][backend] = value ? *value : nlohmann::json();
      std::snprintf(line, sizeof line, " %22s", cell(value).c_str());
      out << line;
    }
    out << "\n";
  }
  nlohmann::json comparison = {{"scene", scene.name},
                               {"backends", backends},
                               {"side_by_side", side_by_side},
                               {"summaries", summaries}};
  std::ofstream(options.out_dir / "compare.json") << comparison.dump(2) << "\n";
  out << "written: " << (options.out_dir / "compare.json").string() << "\n";
  return code;
}

}  // namespace granjet
