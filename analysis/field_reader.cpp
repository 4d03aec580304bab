#include "analysis/field_reader.hpp"

#include <hdf5.h>

#include <string>
#include <vector>

#include "analysis/hdf5_handle.hpp"

namespace granjet::analysis {
namespace {

constexpr std::string_view kMean = "/mean";

// The datasets below `group`, by path relative to it ("stress/rz/mean"), in name order.
std::vector<std::string> datasets_below(hid_t file, const std::string& group,
                                        const H5Context& ctx) {
  const H5Handle g = ctx.own(H5Gopen2(file, group.c_str(), H5P_DEFAULT), H5Gclose, "open", group);
  std::vector<std::string> names;
  const auto collect = [](hid_t parent, const char* name, const H5L_info_t*, void* out) -> herr_t {
    H5O_info_t info;
    if (H5Oget_info_by_name(parent, name, &info, H5P_DEFAULT) < 0) return -1;
    if (info.type == H5O_TYPE_DATASET) static_cast<std::vector<std::string>*>(out)->push_back(name);
    return 0;
  };
  ctx.check(H5Lvisit(g.get(), H5_INDEX_NAME, H5_ITER_INC, collect, &names), "list", group);
  return names;
}

ShapedValues read_shaped(hid_t file, const std::string& path, const H5Context& ctx) {
  const H5Handle set = ctx.own(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose, "open", path);
  const H5Handle space = ctx.own(H5Dget_space(set.get()), H5Sclose, "read the shape of", path);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (rank < 0 || n < 0) ctx.fail("read the shape of", path);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0)
    ctx.fail("read the shape of", path);
  ShapedValues out{{dims.begin(), dims.end()}, std::vector<double>(static_cast<std::size_t>(n))};
  ctx.check(H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()),
            "read", path);
  return out;
}

std::vector<double> read_doubles(hid_t file, const std::string& path, const H5Context& ctx) {
  return read_shaped(file, path, ctx).values;
}

bool ends_with(const std::string& s, std::string_view tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// "stress/rz/mean" -> "stress.rz": the writer nests dotted names.
std::string column_name(const std::string& path) {
  std::string name = path.substr(0, path.size() - kMean.size());
  for (char& c : name)
    if (c == '/') c = '.';
  return name;
}

// Every <path>/mean below `group` as one column of a table of `rows` rows (the run's value),
// plus the plain datasets named in `plain` (abscissae stored once).
Table read_table(hid_t file, const std::string& group, std::size_t rows,
                 const std::vector<std::string>& plain, const H5Context& ctx) {
  Table table(rows);
  const auto fill = [&](const std::string& name, const std::vector<double>& values) {
    if (values.size() != rows) ctx.fail("find " + std::to_string(rows) + " rows in", name);
    for (std::size_t row = 0; row < rows; ++row) table.set(name, row, values[row]);
  };
  for (const std::string& name : plain) fill(name, read_doubles(file, group + "/" + name, ctx));
  for (const std::string& path : datasets_below(file, group, ctx))
    if (ends_with(path, kMean) && path.rfind("mesh/", 0) != 0 && path.rfind("layout/", 0) != 0)
      fill(column_name(path), read_doubles(file, group + "/" + path, ctx));
  return table;
}

std::size_t rows_of(hid_t file, const std::string& dataset, const H5Context& ctx) {
  return read_doubles(file, dataset, ctx).size();
}

}  // namespace

ShapedValues read_shaped_values(const std::filesystem::path& file, const std::string& dataset) {
  const H5Context ctx(file, H5Context::Role::kInput);
  const H5Handle f = ctx.open_read_only();
  return read_shaped(f.get(), dataset, ctx);
}

std::vector<double> read_analysis_values(const std::filesystem::path& file,
                                         const std::string& dataset) {
  return read_shaped_values(file, dataset).values;
}

std::vector<std::string> list_datasets(const std::filesystem::path& file,
                                       const std::string& group) {
  const H5Context ctx(file, H5Context::Role::kInput);
  const H5Handle f = ctx.open_read_only();
  return datasets_below(f.get(), group, ctx);
}

bool has_analysis(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return false;
  const H5Context ctx(file, H5Context::Role::kInput);
  if (H5Fis_hdf5(file.c_str()) <= 0) return false;
  try {
    const H5Handle f = ctx.open_read_only();
    return H5Lexists(f.get(), "/fields", H5P_DEFAULT) > 0 &&
           H5Lexists(f.get(), "/analysis", H5P_DEFAULT) > 0;
  } catch (const std::runtime_error&) {
    return false;
  }
}

RunResult read_run_result(const std::filesystem::path& file) {
  if (!has_analysis(file))
    throw std::runtime_error("'" + file.string() + "' holds no stored analysis (/fields)");
  const H5Context ctx(file, H5Context::Role::kInput);
  const H5Handle f = ctx.open_read_only();
  int seeds = 0;
  ctx.check(H5Aread(ctx.own(H5Aopen_by_name(f.get(), "/fields", "seeds", H5P_DEFAULT, H5P_DEFAULT),
                            H5Aclose, "open", "/fields attribute seeds")
                        .get(),
                    H5T_NATIVE_INT, &seeds),
            "read", "/fields attribute seeds");
  if (seeds != 1)
    throw std::runtime_error("'" + file.string() + "' holds an ensemble of " +
                             std::to_string(seeds) + " seeds, not one run");

  RunResult r;
  r.edges.lateral = read_doubles(f.get(), "/fields/mesh/lateral", ctx);
  r.edges.height = read_doubles(f.get(), "/fields/mesh/height", ctx);
  // Files written before the attribute existed measured from the default origin, 0.
  if (H5Aexists_by_name(f.get(), "/fields", "height_origin", H5P_DEFAULT) > 0)
    ctx.check(H5Aread(ctx.own(H5Aopen_by_name(f.get(), "/fields", "height_origin", H5P_DEFAULT,
                                              H5P_DEFAULT),
                              H5Aclose, "open", "/fields attribute height_origin")
                          .get(),
                      H5T_NATIVE_DOUBLE, &r.edges.height_origin),
              "read", "/fields attribute height_origin");
  const std::size_t bins = (r.edges.lateral.size() - 1) * (r.edges.height.size() - 1);
  r.layout = Table(bins);
  for (const std::string& name : datasets_below(f.get(), "/fields/layout", ctx)) {
    const std::vector<double> values = read_doubles(f.get(), "/fields/layout/" + name, ctx);
    if (values.size() != bins) ctx.fail("find " + std::to_string(bins) + " bins in", name);
    for (std::size_t row = 0; row < bins; ++row) r.layout.set(name, row, values[row]);
  }
  r.fields = read_table(f.get(), "/fields", bins, {}, ctx);
  r.global = read_table(f.get(), "/analysis/global", 1, {}, ctx);
  r.vdf =
      read_table(f.get(), "/analysis/vdf", rows_of(f.get(), "/analysis/vdf/c", ctx), {"c"}, ctx);
  if (H5Lexists(f.get(), "/analysis/azimuth", H5P_DEFAULT) > 0)
    r.azimuth = read_table(f.get(), "/analysis/azimuth",
                           rows_of(f.get(), "/analysis/azimuth/phi", ctx), {"phi"}, ctx);
  return r;
}

}  // namespace granjet::analysis
