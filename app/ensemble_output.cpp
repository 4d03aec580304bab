#include "app/ensemble_output.hpp"

#include "analysis/analysis_json.hpp"
#include "analysis/atomic_file.hpp"
#include "analysis/field_reader.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/h5md_writer.hpp"

namespace granjet {

std::filesystem::path member_file(const std::filesystem::path& file, std::uint64_t seed) {
  if (file.empty()) return file;
  std::filesystem::path f = file;
  return f.replace_extension(".seed" + std::to_string(seed) + file.extension().string());
}

namespace {

// A new file each time (never a merge into what was there): an H5MD file without frames whose
// metadata are the first member's, listing the members, with the combined /fields and
// /analysis; written as .partial and renamed when complete, like a run's file.
template <int D>
void write_ensemble_file(const std::filesystem::path& out_file,
                         const std::vector<std::filesystem::path>& combined,
                         const analysis::EnsembleResult& result) {
  const analysis::FileSummary first = analysis::read_summary(combined.front());
  analysis::RunMetadata meta;
  meta.creator_version = first.creator_version;
  meta.backend = first.backend;
  meta.scene_ini = first.scene_ini;
  meta.dimension = D;
  const std::filesystem::path here = out_file.parent_path().empty() ? "." : out_file.parent_path();
  for (const std::filesystem::path& member : combined)
    meta.members.push_back(std::filesystem::relative(member, here).string());
  analysis::H5mdWriter<D> writer(out_file, meta, 1);
  analysis::store_ensemble(writer.complete(), result, out_file);
  writer.publish();
}

}  // namespace

int write_ensemble(const std::filesystem::path& out_file, const std::filesystem::path& summary,
                   nlohmann::json header, const std::vector<EnsembleMember>& members,
                   int dimension) {
  std::vector<analysis::RunResult> runs;
  std::vector<std::filesystem::path> combined;
  nlohmann::json listed = nlohmann::json::array();
  for (const EnsembleMember& m : members) {
    if (!analysis::has_analysis(m.output)) continue;
    runs.push_back(analysis::read_run_result(m.output));
    combined.push_back(m.output);
    listed.push_back({{"seed", m.seed}, {"output", m.output.string()}});
  }
  if (runs.empty()) return 0;
  const analysis::EnsembleResult result = analysis::combine_runs(runs, dimension);
  if (dimension == 2)
    write_ensemble_file<2>(out_file, combined, result);
  else
    write_ensemble_file<3>(out_file, combined, result);
  if (!summary.empty()) {
    header["runs"] = listed;
    header["output"] = out_file.string();
    header["analysis"] = analysis::to_json(result);
    write_json_atomically(summary, header);
  }
  return static_cast<int>(runs.size());
}

void write_json_atomically(const std::filesystem::path& path, const nlohmann::json& j) {
  analysis::write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

}  // namespace granjet
