#include "analysis/h5md_reader.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <new>
#include <optional>
#include <span>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "analysis/checkpoint_file.hpp"
#include "analysis/hdf5_handle.hpp"

namespace granjet::analysis {
namespace {

constexpr const char* kParameters = "/parameters/granjet";
constexpr const char* kScene = "/parameters/granjet/scene";
constexpr const char* kRequestedScene = "/parameters/granjet/requested_scene";
constexpr const char* kMembers = "/parameters/granjet/members";
constexpr const char* kFrameStep = "/particles/all/position/step";
constexpr const char* kFrameTime = "/particles/all/position/time";
constexpr const char* kFrameGrains = "/observables/frame_grains/value";
constexpr const char* kPosition = "/particles/all/position/value";
constexpr const char* kVelocity = "/particles/all/velocity/value";
constexpr const char* kRadius = "/particles/all/radius/value";
constexpr const char* kId = "/particles/all/id/value";
constexpr const char* kPresent = "/particles/all/present/value";
constexpr const char* kObservableStep = "/observables/kinetic_energy/step";
// The series of one row per frame that readers use, with their ranks (kPresent: when stored).
constexpr std::array<std::pair<const char*, int>, 6> kFrameSeries = {
    {{kFrameTime, 1}, {kFrameGrains, 1}, {kPosition, 3}, {kVelocity, 3}, {kRadius, 2}, {kId, 2}}};

template <class T>
hid_t native_type() {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::int64_t>);
  return std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
}

// A granjet H5MD file opened read-only, with the few typed reads the callers need.
class H5mdInput {
 public:
  explicit H5mdInput(const std::filesystem::path& file) : ctx_(file, H5Context::Role::kInput) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec) || H5Fis_hdf5(file.c_str()) <= 0) {
      throw InputError(file.string(), "is not a readable HDF5 file");
    }
    file_ = ctx_.open_read_only();
    // Both are required by granjet's layout; other H5MD writers lack the second.
    for (const char* group : {"/h5md", kParameters}) {
      if (H5Lexists(file_.get(), group, H5P_DEFAULT) <= 0) {
        throw InputError(file.string(),
                         std::string("is not a granjet H5MD file (no ") + group + ")");
      }
    }
  }

  [[noreturn]] void fail(std::string_view action, std::string_view object) const {
    ctx_.fail(action, object);
  }

  void read_ints(const char* object, const char* name, std::span<int> out) const {
    const std::string what = std::string(object) + " attribute " + name;
    const H5Handle attribute = open_attribute(object, name);
    const H5Handle space = ctx_.own(H5Aget_space(attribute.get()), H5Sclose, "query", what);
    if (H5Sget_simple_extent_npoints(space.get()) != static_cast<hssize_t>(out.size())) {
      fail("find " + std::to_string(out.size()) + " value(s) in", what);
    }
    ctx_.check(H5Aread(attribute.get(), H5T_NATIVE_INT, out.data()), "read", what);
  }

  std::string string_attribute(const char* object, const char* name) const {
    const std::string what = std::string(object) + " attribute " + name;
    const H5Handle attribute = open_attribute(object, name);
    const H5Handle type = ctx_.own(H5Aget_type(attribute.get()), H5Tclose, "query", what);
    const H5Handle space = ctx_.own(H5Aget_space(attribute.get()), H5Sclose, "query", what);
    return fixed_string(type.get(), space.get(), what,
                        [&](char* buffer) { return H5Aread(attribute.get(), type.get(), buffer); });
  }

  // Whether the link exists, with each group on the way (H5Lexists fails on a missing one).
  bool exists(const std::string& name) const {
    for (std::size_t slash = name.find('/', 1);; slash = name.find('/', slash + 1)) {
      if (H5Lexists(file_.get(), name.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return false;
      if (slash == std::string::npos) return true;
    }
  }

  std::string string_dataset(const char* name) const {
    const OpenDataset scalar = open_dataset(name, 0);
    const H5Handle type = ctx_.own(H5Dget_type(scalar.set.get()), H5Tclose, "query", name);
    return fixed_string(type.get(), scalar.space.get(), name, [&](char* buffer) {
      return H5Dread(scalar.set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
    });
  }

  // The shape of `dataset`, which must have `rank` axes.
  std::vector<hsize_t> extent(const char* dataset, int rank) const {
    const OpenDataset open = open_dataset(dataset, rank);
    std::vector<hsize_t> dims(rank);
    ctx_.check(H5Sget_simple_extent_dims(open.space.get(), dims.data(), nullptr), "query", dataset);
    return dims;
  }

  // Reads the block [start, start + count) of `dataset`, densely packed, into `out`.
  void read(const char* dataset, const std::vector<hsize_t>& start,
            const std::vector<hsize_t>& count, hid_t type, void* out) const {
    if (std::find(count.begin(), count.end(), 0) != count.end()) return;
    const int rank = static_cast<int>(count.size());
    const OpenDataset open = open_dataset(dataset, rank);
    ctx_.check(H5Sselect_hyperslab(open.space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                   count.data(), nullptr),
               "select in", dataset);
    const H5Handle memory = ctx_.own(H5Screate_simple(rank, count.data(), nullptr), H5Sclose,
                                     "create a dataspace for", dataset);
    ctx_.check(H5Dread(open.set.get(), type, memory.get(), open.space.get(), H5P_DEFAULT, out),
               "read", dataset);
  }

  template <class T>
  T element(const char* dataset, hsize_t index) const {
    T value{};
    read(dataset, {index}, {1}, native_type<T>(), &value);
    return value;
  }

 private:
  H5Handle open_attribute(const char* object, const char* name) const {
    return ctx_.own(H5Aopen_by_name(file_.get(), object, name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
                    "open", std::string(object) + " attribute " + name);
  }
  struct OpenDataset {
    H5Handle set;
    H5Handle space;
  };
  // Opens `name`, whose dataspace must have `rank` axes (0: scalar).
  OpenDataset open_dataset(const char* name, int rank) const {
    OpenDataset open{ctx_.own(H5Dopen2(file_.get(), name, H5P_DEFAULT), H5Dclose, "open", name),
                     {}};
    open.space = ctx_.own(H5Dget_space(open.set.get()), H5Sclose, "query", name);
    if (H5Sget_simple_extent_ndims(open.space.get()) != rank) {
      fail("find " + std::to_string(rank) + " axes in", name);
    }
    return open;
  }
  // granjet writes only scalar, fixed-length, NUL-terminated strings; reading anything else
  // into one buffer would overrun it.
  template <class Read>
  std::string fixed_string(hid_t type, hid_t space, const std::string& what, Read read) const {
    if (H5Tget_class(type) != H5T_STRING || H5Tis_variable_str(type) != 0 ||
        H5Sget_simple_extent_npoints(space) != 1) {
      fail("read a fixed-length string from", what);
    }
    std::string value(H5Tget_size(type), '\0');
    ctx_.check(read(value.data()), "read", what);
    value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
    return value;
  }

  H5Context ctx_;
  H5Handle file_;
};

}  // namespace

FileSummary read_summary(const std::filesystem::path& file) {
  const H5mdInput in(file);
  FileSummary summary;
  in.read_ints("/h5md", "version", summary.h5md_version);
  summary.creator = in.string_attribute("/h5md/creator", "name");
  summary.creator_version = in.string_attribute("/h5md/creator", "version");
  summary.backend = in.string_attribute(kParameters, "backend");
  summary.status = in.string_attribute(kParameters, "status");
  in.read_ints(kParameters, "dimension", std::span(&summary.dimension, 1));
  if (summary.dimension != 2 && summary.dimension != 3)
    throw InputError(file.string(), "stores dimension " + std::to_string(summary.dimension) +
                                        "; granjet writes 2 or 3");
  summary.scene_ini = in.string_dataset(kScene);
  if (in.exists(kRequestedScene)) summary.requested_scene_ini = in.string_dataset(kRequestedScene);
  // A run's own file, not yet renamed: even one marked complete may have been killed while it
  // added its fields, and resumes from its checkpoint.
  if (file.extension() == ".partial") {
    if (const std::optional<double> time = checkpoint_time(checkpoint_path(file))) {
      summary.checkpoint = true;
      summary.checkpoint_time = *time;
    }
  }
  if (in.exists(kMembers)) {
    std::istringstream lines(in.string_dataset(kMembers));
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) summary.members.push_back(line);
  }
  // The frames every per-frame dataset holds: a run killed while it appended one holds it in
  // some of them only (resume drops it).
  summary.frames = in.extent(kFrameStep, 1)[0];
  for (const auto& [set, rank] : kFrameSeries)
    summary.frames = std::min<std::size_t>(summary.frames, in.extent(set, rank)[0]);
  if (in.exists(kPresent))
    summary.frames = std::min<std::size_t>(summary.frames, in.extent(kPresent, 2)[0]);
  summary.max_grains = in.extent(kPosition, 3)[1];
  summary.observable_rows = in.extent(kObservableStep, 1)[0];
  if (summary.frames > 0) {
    summary.first_time = in.element<double>(kFrameTime, 0);
    summary.last_time = in.element<double>(kFrameTime, summary.frames - 1);
    summary.last_step = in.element<std::int64_t>(kFrameStep, summary.frames - 1);
  }
  return summary;
}

// A damaged or foreign file must not reach the analysis: it indexes by id and divides by radii.
template <int D>
void validate_frame(const Frame<D>& frame, const std::filesystem::path& file, std::size_t index) {
  const auto bad = [&](const std::string& what) {
    return InputError(file.string(), "frame " + std::to_string(index) + ": " + what);
  };
  if (!std::isfinite(frame.time)) throw bad("its time is not finite");
  for (std::size_t k = 0; k < frame.id.size(); ++k) {
    const std::string row =
        "row " + std::to_string(k) + " (grain id " + std::to_string(frame.id[k]) + ")";
    if (!frame.position[k].allFinite() || !frame.velocity[k].allFinite())
      throw bad(row + ": a position or velocity that is not finite");
    if (!(std::isfinite(frame.radius[k]) && frame.radius[k] > 0.0))
      throw bad(row + ": radius " + std::to_string(frame.radius[k]) +
                " is not positive and finite");
  }
}

template <int D>
Frame<D> read_frame(const std::filesystem::path& file, std::size_t index) {
  // Vectors are read straight into the storage of std::vector<Vec<D>>.
  static_assert(sizeof(Vec<D>) == D * sizeof(double));
  const H5mdInput in(file);
  int dimension = 0;
  in.read_ints(kParameters, "dimension", std::span(&dimension, 1));
  if (dimension != D) {
    throw InputError(file.string(), "holds " + std::to_string(dimension) + "D grains, not " +
                                        std::to_string(D) + "D");
  }
  const hsize_t frames = in.extent(kFrameStep, 1)[0];
  if (index >= frames) {
    throw std::runtime_error("'" + file.string() + "' has " + std::to_string(frames) +
                             " frames, no frame " + std::to_string(index));
  }
  // Each grain id has its row; the rows of removed grains hold id -1 and are left out.
  // A damaged header can claim any number of rows: the four series must agree, and what they
  // claim must fit in memory.
  const hsize_t rows = in.extent(kPosition, 3)[1];
  if (in.extent(kId, 2)[1] != rows || in.extent(kVelocity, 3)[1] != rows ||
      in.extent(kRadius, 2)[1] != rows)
    in.fail("read", "frames whose id, position, velocity and radius rows disagree");
  std::vector<GrainId> id;
  std::vector<Vec<D>> position, velocity;
  std::vector<double> radius;
  try {
    id.resize(rows);
    position.resize(rows);
    velocity.resize(rows);
    radius.resize(rows);
  } catch (const std::bad_alloc&) {
    in.fail("hold", "the " + std::to_string(rows) + " grains a frame claims");
  }
  in.read(kId, {index, 0}, {1, rows}, H5T_NATIVE_INT64, id.data());
  in.read(kPosition, {index, 0, 0}, {1, rows, D}, H5T_NATIVE_DOUBLE, position.data());
  in.read(kVelocity, {index, 0, 0}, {1, rows, D}, H5T_NATIVE_DOUBLE, velocity.data());
  in.read(kRadius, {index, 0}, {1, rows}, H5T_NATIVE_DOUBLE, radius.data());
  Frame<D> frame;
  frame.step = in.element<std::int64_t>(kFrameStep, index);
  frame.time = in.element<double>(kFrameTime, index);
  // Files written before granjet kept a row per id (no present list) hold each frame's grains
  // in rows 0..n-1, sorted by id.
  const bool row_per_id = in.exists(kPresent);
  for (hsize_t r = 0; r < rows; ++r) {
    if (id[r] == -1) continue;
    if (row_per_id ? id[r] != static_cast<GrainId>(r) : id[r] < 0 || (r > 0 && id[r] <= id[r - 1]))
      throw InputError(
          file.string(),
          "frame " + std::to_string(index) + ": row " + std::to_string(r) + " holds grain id " +
              std::to_string(id[r]) +
              (row_per_id ? " (granjet stores grain r in row r, or -1)" : " (ids must increase)"));
    frame.id.push_back(id[r]);
    frame.position.push_back(position[r]);
    frame.velocity.push_back(velocity[r]);
    frame.radius.push_back(radius[r]);
  }
  const std::int64_t grains = in.element<std::int64_t>(kFrameGrains, index);
  if (grains != static_cast<std::int64_t>(frame.id.size()))
    in.fail("find the " + std::to_string(frame.id.size()) + " grains of frame " +
                std::to_string(index) + " counted in",
            kFrameGrains);
  validate_frame(frame, file, index);
  return frame;
}

template Frame<2> read_frame<2>(const std::filesystem::path&, std::size_t);
template Frame<3> read_frame<3>(const std::filesystem::path&, std::size_t);

}  // namespace granjet::analysis
