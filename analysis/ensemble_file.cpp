#include "analysis/ensemble_file.hpp"

#include "analysis/field_reader.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/h5md_writer.hpp"

namespace granjet::analysis {
namespace {

template <int D>
EnsembleResult write_file(const std::filesystem::path& out_file,
                          const std::vector<std::filesystem::path>& members,
                          const std::vector<RunResult>& runs) {
  const FileSummary first = read_summary(members.front());
  RunMetadata meta;
  meta.creator_version = first.creator_version;
  meta.backend = first.backend;
  meta.scene_ini = first.scene_ini;
  meta.requested_scene_ini = first.requested_scene_ini;
  meta.dimension = D;
  const std::filesystem::path here = out_file.parent_path().empty() ? "." : out_file.parent_path();
  for (const std::filesystem::path& member : members)
    meta.members.push_back(std::filesystem::relative(member, here).string());
  H5mdWriter<D> writer(out_file, meta, 1);
  EnsembleResult result = write_ensemble(writer.complete(), runs, D, out_file);
  writer.publish();
  return result;
}

}  // namespace

EnsembleResult write_ensemble_file(const std::filesystem::path& out_file,
                                   const std::vector<std::filesystem::path>& members,
                                   int dimension) {
  std::vector<RunResult> runs;
  for (const std::filesystem::path& member : members) runs.push_back(read_run_result(member));
  return with_dimension(dimension, [&](auto d) { return write_file<d>(out_file, members, runs); });
}

}  // namespace granjet::analysis
