#include "run/output_paths.hpp"

#include "core/errors.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

fs::path with_suffix(fs::path p, const std::string& suffix) {
  p += suffix;
  return p;
}

fs::path with_extension(fs::path p, const std::string& extension) {
  return p.replace_extension(extension);
}

// Hard links and symbolic links to one file count as that file.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

}  // namespace

std::vector<OutputPath> run_outputs(const fs::path& out, const fs::path& summary,
                                    const std::string& whose) {
  std::vector<OutputPath> files = {
      {"--out", out, whose + " file"},
      {"--out", with_suffix(out, ".partial"), whose + " file while it is written"},
      {"--out", with_suffix(out, ".checkpoint"), whose + " checkpoint"},
      {"--out", with_suffix(out, ".checkpoint.partial"), whose + " checkpoint while it is written"},
      {"--out", with_extension(out, ".xmf"), whose + " XDMF sidecar"},
      {"--out", with_extension(out, ".fields.xmf"), whose + " fields sidecar"},
      {"--out", with_extension(out, ".log"), whose + " log"}};
  if (!summary.empty()) {
    files.push_back({"--summary", summary, whose + " summary"});
    files.push_back(
        {"--summary", with_suffix(summary, ".partial"), whose + " summary while it is written"});
  }
  return files;
}

void check_outputs(const fs::path& input, const std::vector<OutputPath>& outputs) {
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const OutputPath& o = outputs[k];
    if (same_file(o.path, input))
      throw InputError(o.option, "'" + o.path.string() + "' is the input file " + input.string() +
                                     "; it would be overwritten");
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(o.path, ec);
    if (fs::exists(status) && !fs::is_regular_file(fs::status(o.path, ec)))
      throw InputError(
          o.option, "'" + o.path.string() + "' exists and is not a regular file; name a new file");
    const fs::path parent = o.path.parent_path().empty() ? fs::path(".") : o.path.parent_path();
    if (!fs::is_directory(parent, ec))
      throw InputError(o.option, "'" + o.path.string() + "': no directory " + parent.string());
    for (std::size_t j = 0; j < k; ++j)
      if (same_file(o.path, outputs[j].path))
        throw InputError(o.option, "'" + o.path.string() + "' would be both " + o.role + " and " +
                                       outputs[j].role + " (" + outputs[j].option + ")");
  }
}

}  // namespace granjet
