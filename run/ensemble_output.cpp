#include "run/ensemble_output.hpp"

#include "analysis/analysis_json.hpp"
#include "analysis/atomic_file.hpp"
#include "analysis/ensemble_file.hpp"
#include "analysis/field_reader.hpp"

namespace granjet {

std::filesystem::path member_file(const std::filesystem::path& file, std::uint64_t seed) {
  if (file.empty()) return file;
  std::filesystem::path f = file;
  return f.replace_extension(".seed" + std::to_string(seed) + file.extension().string());
}

int merge_ensemble(const std::filesystem::path& out_file, const std::filesystem::path& summary,
                   nlohmann::json header, const std::vector<EnsembleMember>& members,
                   int dimension) {
  std::vector<std::filesystem::path> combined;
  nlohmann::json listed = nlohmann::json::array();
  for (const EnsembleMember& m : members) {
    if (!analysis::has_analysis(m.output)) continue;
    combined.push_back(m.output);
    listed.push_back({{"seed", m.seed}, {"output", m.output.string()}});
  }
  if (combined.empty()) return 0;
  const analysis::EnsembleResult result =
      analysis::write_ensemble_file(out_file, combined, dimension);
  if (!summary.empty()) {
    header["runs"] = listed;
    header["output"] = out_file.string();
    header["analysis"] = analysis::to_json(result);
    write_json_atomically(summary, header);
  }
  return static_cast<int>(combined.size());
}

void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& j) {
  analysis::write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

}  // namespace granjet
