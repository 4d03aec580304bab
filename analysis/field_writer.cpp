#include "analysis/field_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

#include "analysis/hdf5_copy.hpp"
#include "analysis/hdf5_handle.hpp"

namespace granjet::analysis {
namespace {

class GroupWriter {
 public:
  explicit GroupWriter(const std::filesystem::path& file) : ctx_(file) {
    file_ = std::filesystem::exists(file)
                ? ctx_.own(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open",
                           "the HDF5 file")
                : ctx_.own(H5Fcreate(file.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT),
                           H5Fclose, "create", "the HDF5 file");
    links_ = ctx_.own(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "create", "link properties");
    ctx_.check(H5Pset_create_intermediate_group(links_.get(), 1), "set", "link properties");
  }

  // Removes an earlier `group` (a re-analysis replaces it) and creates it afresh.
  void fresh_group(const std::string& group) {
    if (H5Lexists(file_.get(), group.c_str(), H5P_DEFAULT) > 0)
      ctx_.check(H5Ldelete(file_.get(), group.c_str(), H5P_DEFAULT), "replace", group);
    ctx_.own(H5Gcreate2(file_.get(), group.c_str(), links_.get(), H5P_DEFAULT, H5P_DEFAULT),
             H5Gclose, "create", group);
  }

  template <class T>
  void dataset(const std::string& name, const std::vector<hsize_t>& dims,
               const std::vector<T>& data) {
    const hid_t type = std::is_same_v<T, int> ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
    const H5Handle space = ctx_.dataspace(dims);
    const H5Handle set = ctx_.own(H5Dcreate2(file_.get(), name.c_str(), type, space.get(),
                                             links_.get(), H5P_DEFAULT, H5P_DEFAULT),
                                  H5Dclose, "create", name);
    ctx_.check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), "write",
               name);
  }

  void attribute(const std::string& object, const char* name, int value) {
    write_attribute(object, name, H5T_NATIVE_INT, ctx_.dataspace({}).get(), &value);
  }
  void attribute(const std::string& object, const char* name, double value) {
    write_attribute(object, name, H5T_NATIVE_DOUBLE, ctx_.dataspace({}).get(), &value);
  }
  void attribute(const std::string& object, const char* name, const std::string& value) {
    ctx_.write_string_attribute(file_.get(), object, name, value);
  }
  // A list of names as one fixed-length string array.
  void attribute(const std::string& object, const char* name,
                 const std::vector<std::string>& values) {
    std::size_t width = 1;
    for (const std::string& v : values) width = std::max(width, v.size() + 1);
    std::string packed(width * values.size(), '\0');
    for (std::size_t k = 0; k < values.size(); ++k)
      packed.replace(k * width, values[k].size(), values[k]);
    write_attribute(object, name, ctx_.string_type(width).get(),
                    ctx_.dataspace({values.size()}).get(), packed.data());
  }

  // Closes the file, reporting a failure to write its last metadata.
  void close() { ctx_.check(file_.reset(), "close", "the file"); }

 private:
  void write_attribute(const std::string& object, const char* name, hid_t type, hid_t space,
                       const void* data) {
    ctx_.write_attribute(file_.get(), object, name, type, space, data);
  }

  H5Context ctx_;
  H5Handle file_;
  H5Handle links_;
};

// Every column of `table` as <group>/<path>/{mean,std,sem,count} of shape `dims`.
void write_spreads(GroupWriter& out, const std::string& group, const EnsembleTable& table,
                   const std::vector<hsize_t>& dims) {
  for (const std::string& name : table.names()) {
    std::vector<double> mean, std, sem;
    std::vector<int> count;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      const Spread& s = table.at(row, name);
      mean.push_back(s.mean);
      std.push_back(s.std);
      sem.push_back(s.sem);
      count.push_back(s.count);
    }
    const std::string base = group + "/" + field_path(name) + "/";
    out.dataset(base + "mean", dims, mean);
    out.dataset(base + "std", dims, std);
    out.dataset(base + "sem", dims, sem);
    out.dataset(base + "count", dims, count);
  }
}

// A distribution: its abscissa once, the other columns as spreads.
void write_distribution(GroupWriter& out, const std::string& group, const EnsembleTable& table,
                        const std::string& abscissa) {
  const std::vector<hsize_t> dims{table.rows()};
  out.dataset(group + "/" + abscissa, dims, table.means(abscissa));
  for (const std::string& name : table.names()) {
    if (name == abscissa) continue;
    std::vector<double> mean, std, sem;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      mean.push_back(table.at(row, name).mean);
      std.push_back(table.at(row, name).std);
      sem.push_back(table.at(row, name).sem);
    }
    const std::string base = group + "/" + field_path(name) + "/";
    out.dataset(base + "mean", dims, mean);
    out.dataset(base + "std", dims, std);
    out.dataset(base + "sem", dims, sem);
  }
}

std::vector<hsize_t> mesh_dims(const EnsembleResult& r) {
  return {r.edges.height.size() - 1, r.edges.lateral.size() - 1};
}

}  // namespace

std::string field_path(std::string name) {
  for (char& c : name)
    if (c == '.') c = '/';
  return name;
}

void write_analysis_hdf5(const std::filesystem::path& file, const EnsembleResult& result) {
  GroupWriter out(file);
  const std::vector<hsize_t> dims = mesh_dims(result);

  out.fresh_group("/fields");
  out.attribute("/fields", "dimension", result.dimension);
  out.attribute("/fields", "seeds", result.seeds);
  out.attribute("/fields", "coordinates",
                std::string(result.dimension == 3 ? "cylindrical" : "cartesian"));
  out.attribute("/fields", "height_origin", result.edges.height_origin);
  out.dataset("/fields/mesh/lateral", {result.edges.lateral.size()}, result.edges.lateral);
  out.dataset("/fields/mesh/height", {result.edges.height.size()}, result.edges.height);
  const FieldCells cells = field_cells(result);
  out.dataset("/fields/mesh/points", {cells.sectors + 1, cells.layers + 1, cells.lateral + 1, 3},
              cells.corners);
  for (const std::string& name : result.layout.names())
    out.dataset("/fields/layout/" + name, dims, result.layout.column(name));
  write_spreads(out, "/fields", result.fields, dims);

  out.fresh_group("/analysis");
  write_spreads(out, "/analysis/global", result.global, {});
  write_distribution(out, "/analysis/vdf", result.vdf, "c");
  if (result.azimuth.rows() > 0)
    write_distribution(out, "/analysis/azimuth", result.azimuth, "phi");
  for (const FitResult& fit : result.fits) {
    const std::string group = "/analysis/fits/" + fit.law;
    const std::vector<hsize_t> p{fit.parameters.size()};
    out.dataset(group + "/value", p, std::vector<double>(fit.value.begin(), fit.value.end()));
    out.dataset(group + "/error", p, std::vector<double>(fit.error.begin(), fit.error.end()));
    out.attribute(group, "parameters", fit.parameters);
    out.attribute(group, "ssr", fit.ssr);
    out.attribute(group, "points", fit.points);
    out.attribute(group, "converged", fit.converged ? 1.0 : 0.0);
  }
  out.close();
}

void copy_without_analysis(const std::filesystem::path& source,
                           const std::filesystem::path& target) {
  copy_hdf5_except(source, target, {"fields", "analysis"});
}

std::filesystem::path fields_sidecar(const std::filesystem::path& file) {
  std::filesystem::path xmf = file;
  return xmf.replace_extension(".fields.xmf");
}

EnsembleResult write_ensemble(const std::filesystem::path& file, std::span<const RunResult> runs,
                              int dimension, const std::filesystem::path& published_as) {
  EnsembleResult result = combine_runs(runs, dimension);
  write_analysis_hdf5(file, result);
  const std::filesystem::path& name = published_as.empty() ? file : published_as;
  write_fields_xdmf(fields_sidecar(name), name.filename().string(), result);
  return result;
}

}  // namespace granjet::analysis
