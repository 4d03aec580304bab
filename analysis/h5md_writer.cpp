#include "analysis/h5md_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "analysis/file_lock.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/hdf5_handle.hpp"
#include "analysis/xdmf_sidecar.hpp"

namespace granjet::analysis {
namespace {

// Grains per chunk along the grain axis: large enough for efficient I/O, small enough that the
// chunks beyond a shrunken grain count are never allocated.
constexpr hsize_t kChunkGrains = 16384;
// Rows per chunk of the scalar time series (step, time, observables).
constexpr hsize_t kChunkRows = 1024;

constexpr std::array<const char*, 4> kEnergies = {"kinetic_energy", "rotational_energy",
                                                  "elastic_energy", "energy_dissipated"};

std::filesystem::path partial_path(std::filesystem::path path) {
  path += ".partial";
  return path;
}

}  // namespace

namespace detail {

class H5mdFile {
 public:
  // One grain per row, sorted by id so that frames line up for analysis.
  struct FrameRows {
    std::vector<GrainId> id;
    std::vector<double> position;  // row-major [grains][dimension]
    std::vector<double> velocity;
    std::vector<double> radius;
  };

  H5mdFile(std::filesystem::path path, const RunMetadata& meta, int dimension,
           std::size_t max_grains);
  // Reopens a run's .partial at its checkpoint: frames and observables written after it are
  // dropped, and the status is "running" again.
  H5mdFile(std::filesystem::path path, int dimension);
  void write_checkpoint(StateArchive archive);
  void replace_scene(const std::string& scene_ini);
  void write_frame(std::int64_t step, double time, const FrameRows& rows);
  void write_observables(std::int64_t step, double time, const Observables& obs);
  std::filesystem::path complete();
  void publish();
  std::filesystem::path abandon(const std::string& reason);

 private:
  // An extendable dataset; extent is its current shape [rows, row shape...].
  struct Dataset {
    H5Handle handle;
    std::string name;
    std::vector<hsize_t> extent;
  };
  struct Datasets {
    Dataset frame_step, frame_time, frame_grains, position, velocity, radius, id;
    Dataset observable_step, observable_time, grains;
    std::array<Dataset, kEnergies.size()> energies;
  };

  H5Handle dataspace(const std::vector<hsize_t>& dims) const;  // scalar when dims is empty
  H5Handle string_type(std::size_t size) const;                // size counts the trailing NUL
  void create_group(const char* name) const;
  void write_attribute(const char* object, const char* name, hid_t type, hid_t space,
                       const void* data) const;
  void write_string_attribute(const char* object, const char* name, const std::string& value) const;
  void write_string_dataset(const char* name, const std::string& value) const;
  Dataset create_series(std::string name, hid_t type, const std::vector<hsize_t>& row_shape,
                        const void* fill) const;
  // H5MD lets elements sampled together share one step and one time dataset.
  void share_step_and_time(const std::string& from, const std::string& to) const;
  void append(Dataset& set, hsize_t valid, hid_t type, const void* data);
  void require_open() const;
  void close();
  Dataset open_series(const std::string& name) const;
  void truncate(Dataset& set, hsize_t rows);

  std::filesystem::path path_;
  H5Context ctx_;
  std::optional<FileLock> lock_;  // from before the .partial is truncated until it is renamed
  int dimension_;
  hsize_t max_grains_;
  H5Handle file_;  // declared before the datasets, so it is closed after them
  H5Handle link_props_;
  Datasets sets_;
  std::vector<XdmfFrame> frames_;
};

H5mdFile::H5mdFile(std::filesystem::path path, const RunMetadata& meta, int dimension,
                   std::size_t max_grains)
    : path_(std::move(path)),
      ctx_(partial_path(path_)),
      dimension_(dimension),
      max_grains_(max_grains) {
  if (max_grains == 0) throw std::invalid_argument("H5mdWriter: max_grains must be positive");
  if (meta.dimension != dimension) {
    throw std::invalid_argument("H5mdWriter<" + std::to_string(dimension) +
                                ">: metadata says dimension " + std::to_string(meta.dimension));
  }
  lock_.emplace(ctx_.file());
  file_ = ctx_.own(H5Fcreate(ctx_.file().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                   H5Fclose, "create", "the HDF5 file");
  // Missing parent groups are created on the way, so every object is made by its full path.
  link_props_ = ctx_.own(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "create", "link properties");
  ctx_.check(H5Pset_create_intermediate_group(link_props_.get(), 1), "set", "link properties");

  create_group("/h5md/author");
  create_group("/h5md/creator");
  const std::array<int, 2> version = {1, 1};
  write_attribute("/h5md", "version", H5T_NATIVE_INT, dataspace({2}).get(), version.data());
  write_string_attribute("/h5md/author", "name", meta.author);
  write_string_attribute("/h5md/creator", "name", meta.creator);
  write_string_attribute("/h5md/creator", "version", meta.creator_version);

  // No axis wraps around, so the box needs no edges.
  create_group("/particles/all/box");
  write_attribute("/particles/all/box", "dimension", H5T_NATIVE_INT, dataspace({}).get(),
                  &dimension_);
  std::string boundary;
  for (int d = 0; d < dimension_; ++d) boundary.append("none", 5);  // with its NUL
  write_attribute("/particles/all/box", "boundary", string_type(5).get(),
                  dataspace({static_cast<hsize_t>(dimension_)}).get(), boundary.data());

  // Rows past a frame's grain count keep these fill values; -1 is H5MD's "no particle" id.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const GrainId no_grain = -1;
  const hsize_t g = max_grains_;
  const auto d = static_cast<hsize_t>(dimension_);
  const std::string all = "/particles/all/";
  sets_.frame_step = create_series(all + "position/step", H5T_NATIVE_INT64, {}, nullptr);
  sets_.frame_time = create_series(all + "position/time", H5T_NATIVE_DOUBLE, {}, nullptr);
  sets_.position = create_series(all + "position/value", H5T_NATIVE_DOUBLE, {g, d}, &nan);
  sets_.velocity = create_series(all + "velocity/value", H5T_NATIVE_DOUBLE, {g, d}, &nan);
  sets_.radius = create_series(all + "radius/value", H5T_NATIVE_DOUBLE, {g}, &nan);
  sets_.id = create_series(all + "id/value", H5T_NATIVE_INT64, {g}, &no_grain);
  sets_.frame_grains =
      create_series("/observables/frame_grains/value", H5T_NATIVE_INT64, {}, nullptr);
  for (const std::string& element :
       {all + "velocity", all + "radius", all + "id", std::string("/observables/frame_grains")}) {
    share_step_and_time(all + "position", element);
  }

  const std::string obs = "/observables/";
  sets_.observable_step =
      create_series(obs + kEnergies[0] + "/step", H5T_NATIVE_INT64, {}, nullptr);
  sets_.observable_time =
      create_series(obs + kEnergies[0] + "/time", H5T_NATIVE_DOUBLE, {}, nullptr);
  for (std::size_t k = 0; k < kEnergies.size(); ++k) {
    sets_.energies[k] =
        create_series(obs + kEnergies[k] + "/value", H5T_NATIVE_DOUBLE, {}, nullptr);
    if (k > 0) share_step_and_time(obs + kEnergies[0], obs + kEnergies[k]);
  }
  sets_.grains = create_series(obs + "grains/value", H5T_NATIVE_INT64, {}, nullptr);
  share_step_and_time(obs + kEnergies[0], obs + "grains");

  create_group("/parameters/granjet");
  write_string_attribute("/parameters/granjet", "backend", meta.backend);
  write_attribute("/parameters/granjet", "dimension", H5T_NATIVE_INT, dataspace({}).get(),
                  &dimension_);
  write_string_attribute("/parameters/granjet", "status", "running");
  write_string_dataset("/parameters/granjet/scene", meta.scene_ini);
  if (!meta.members.empty()) {
    std::string lines;
    for (const std::string& member : meta.members) lines += member + "\n";
    write_string_dataset("/parameters/granjet/members", lines);
  }
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
}

// A dataset, not an attribute: the scene may exceed the 64 KiB attribute limit.
void H5mdFile::write_string_dataset(const char* name, const std::string& value) const {
  const H5Handle type = string_type(value.size() + 1);
  const H5Handle set = ctx_.own(H5Dcreate2(file_.get(), name, type.get(), dataspace({}).get(),
                                           link_props_.get(), H5P_DEFAULT, H5P_DEFAULT),
                                H5Dclose, "create", name);
  ctx_.check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()),
             "write", name);
}

H5mdFile::H5mdFile(std::filesystem::path path, int dimension)
    : path_(std::move(path)), ctx_(partial_path(path_)), dimension_(dimension) {
  lock_.emplace(ctx_.file());
  const StateArchive checkpoint = read_checkpoint(ctx_.file());  // before it is opened to write
  file_ = ctx_.own(H5Fopen(ctx_.file().c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "open",
                   "the HDF5 file");
  link_props_ = ctx_.own(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "create", "link properties");
  ctx_.check(H5Pset_create_intermediate_group(link_props_.get(), 1), "set", "link properties");
  const std::string all = "/particles/all/", obs = "/observables/";
  sets_.frame_step = open_series(all + "position/step");
  sets_.frame_time = open_series(all + "position/time");
  sets_.position = open_series(all + "position/value");
  sets_.velocity = open_series(all + "velocity/value");
  sets_.radius = open_series(all + "radius/value");
  sets_.id = open_series(all + "id/value");
  sets_.frame_grains = open_series(obs + "frame_grains/value");
  sets_.observable_step = open_series(obs + kEnergies[0] + "/step");
  sets_.observable_time = open_series(obs + kEnergies[0] + "/time");
  for (std::size_t k = 0; k < kEnergies.size(); ++k)
    sets_.energies[k] = open_series(obs + kEnergies[k] + "/value");
  sets_.grains = open_series(obs + "grains/value");
  max_grains_ = sets_.position.extent.at(1);
  const auto frames = static_cast<hsize_t>(checkpoint.integer("writer/frames"));
  const auto rows = static_cast<hsize_t>(checkpoint.integer("writer/observable_rows"));
  if (frames > sets_.frame_step.extent[0] || rows > sets_.observable_step.extent[0])
    ctx_.fail("resume at", "a checkpoint that counts more frames than the file holds");
  for (Dataset* set : {&sets_.frame_step, &sets_.frame_time, &sets_.position, &sets_.velocity,
                       &sets_.radius, &sets_.id, &sets_.frame_grains})
    truncate(*set, frames);
  for (Dataset* set : {&sets_.observable_step, &sets_.observable_time, &sets_.grains})
    truncate(*set, rows);
  for (Dataset& set : sets_.energies) truncate(set, rows);
  std::vector<double> time(frames);
  std::vector<std::int64_t> grains(frames);
  if (frames > 0) {
    ctx_.check(H5Dread(sets_.frame_time.handle.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                       H5P_DEFAULT, time.data()),
               "read", sets_.frame_time.name);
    ctx_.check(H5Dread(sets_.frame_grains.handle.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL,
                       H5P_DEFAULT, grains.data()),
               "read", sets_.frame_grains.name);
  }
  for (hsize_t k = 0; k < frames; ++k)
    frames_.push_back({time[k], static_cast<std::size_t>(grains[k])});
  write_string_attribute("/parameters/granjet", "status", "running");
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
}

void H5mdFile::replace_scene(const std::string& scene_ini) {
  require_open();
  const char* name = "/parameters/granjet/scene";
  ctx_.check(H5Ldelete(file_.get(), name, H5P_DEFAULT), "replace", name);
  write_string_dataset(name, scene_ini);
}

H5mdFile::Dataset H5mdFile::open_series(const std::string& name) const {
  H5Handle set = ctx_.own(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose, "open", name);
  const H5Handle space = ctx_.own(H5Dget_space(set.get()), H5Sclose, "query", name);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 1) ctx_.fail("read the shape of", name);
  std::vector<hsize_t> extent(rank);
  ctx_.check(H5Sget_simple_extent_dims(space.get(), extent.data(), nullptr), "query", name);
  return {std::move(set), name, std::move(extent)};
}

void H5mdFile::truncate(Dataset& set, hsize_t rows) {
  set.extent[0] = rows;
  ctx_.check(H5Dset_extent(set.handle.get(), set.extent.data()), "truncate", set.name);
}

// /checkpoint.new takes every entry, then replaces /checkpoint: a run killed while it is
// written keeps the last complete one. It counts the frames and observables written so far, so
// that a resume drops those written after it.
void H5mdFile::write_checkpoint(StateArchive archive) {
  require_open();
  archive.put("writer/frames", static_cast<std::int64_t>(sets_.frame_step.extent[0]));
  archive.put("writer/observable_rows", static_cast<std::int64_t>(sets_.observable_step.extent[0]));
  const std::string fresh = "/checkpoint.new";
  if (H5Lexists(file_.get(), fresh.c_str(), H5P_DEFAULT) > 0)
    ctx_.check(H5Ldelete(file_.get(), fresh.c_str(), H5P_DEFAULT), "replace", fresh);
  const auto store = [&](const std::string& name, hid_t type, std::size_t n, const void* data) {
    const std::string path = fresh + "/" + name;
    const H5Handle set = ctx_.own(H5Dcreate2(file_.get(), path.c_str(), type,
                                             dataspace({static_cast<hsize_t>(n)}).get(),
                                             link_props_.get(), H5P_DEFAULT, H5P_DEFAULT),
                                  H5Dclose, "create", path);
    if (n > 0) ctx_.check(H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "write", path);
  };
  for (const auto& [name, values] : archive.all_reals())
    store(name, H5T_NATIVE_DOUBLE, values.size(), values.data());
  for (const auto& [name, values] : archive.all_integers())
    store(name, H5T_NATIVE_INT64, values.size(), values.data());
  if (H5Lexists(file_.get(), "/checkpoint", H5P_DEFAULT) > 0)
    ctx_.check(H5Ldelete(file_.get(), "/checkpoint", H5P_DEFAULT), "replace", "/checkpoint");
  ctx_.check(H5Lmove(file_.get(), fresh.c_str(), file_.get(), "/checkpoint", H5P_DEFAULT,
                     H5P_DEFAULT),
             "rename", fresh);
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
}

void H5mdFile::write_frame(std::int64_t step, double time, const FrameRows& rows) {
  require_open();
  const hsize_t n = rows.id.size();
  if (n > max_grains_) {
    throw std::invalid_argument("H5mdWriter: " + std::to_string(n) + " grains exceed max_grains " +
                                std::to_string(max_grains_));
  }
  const auto grains = static_cast<std::int64_t>(n);
  append(sets_.frame_step, 1, H5T_NATIVE_INT64, &step);
  append(sets_.frame_time, 1, H5T_NATIVE_DOUBLE, &time);
  append(sets_.frame_grains, 1, H5T_NATIVE_INT64, &grains);
  append(sets_.position, n, H5T_NATIVE_DOUBLE, rows.position.data());
  append(sets_.velocity, n, H5T_NATIVE_DOUBLE, rows.velocity.data());
  append(sets_.radius, n, H5T_NATIVE_DOUBLE, rows.radius.data());
  append(sets_.id, n, H5T_NATIVE_INT64, rows.id.data());
  // A run killed later still leaves this frame readable.
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
  frames_.push_back({time, n});
}

void H5mdFile::write_observables(std::int64_t step, double time, const Observables& obs) {
  require_open();
  const std::array<double, kEnergies.size()> energies = {obs.kinetic_energy, obs.rotational_energy,
                                                         obs.elastic_energy, obs.energy_dissipated};
  append(sets_.observable_step, 1, H5T_NATIVE_INT64, &step);
  append(sets_.observable_time, 1, H5T_NATIVE_DOUBLE, &time);
  for (std::size_t k = 0; k < energies.size(); ++k) {
    append(sets_.energies[k], 1, H5T_NATIVE_DOUBLE, &energies[k]);
  }
  append(sets_.grains, 1, H5T_NATIVE_INT64, &obs.grains);
}

std::filesystem::path H5mdFile::complete() {
  require_open();
  // A complete run resumes nothing; its checkpoint (with its wall time) would only take room.
  for (const char* checkpoint : {"/checkpoint", "/checkpoint.new"})
    if (H5Lexists(file_.get(), checkpoint, H5P_DEFAULT) > 0)
      ctx_.check(H5Ldelete(file_.get(), checkpoint, H5P_DEFAULT), "remove", checkpoint);
  write_string_attribute("/parameters/granjet", "status", "complete");
  close();
  // An ensemble file holds no frames: nothing to draw, and a sidecar of frames that an earlier
  // file of this name held would show what is gone.
  if (frames_.empty())
    std::filesystem::remove(xdmf_path_for(path_));
  else
    write_xdmf_sidecar(xdmf_path_for(path_), path_.filename().string(), dimension_, max_grains_,
                       frames_);
  return ctx_.file();
}

void H5mdFile::publish() {
  std::filesystem::rename(ctx_.file(), path_);
  lock_.reset();
}

std::filesystem::path H5mdFile::abandon(const std::string& reason) {
  require_open();
  write_string_attribute("/parameters/granjet", "status", reason);
  close();
  return ctx_.file();
}

H5Handle H5mdFile::dataspace(const std::vector<hsize_t>& dims) const {
  const hid_t space = dims.empty()
                          ? H5Screate(H5S_SCALAR)
                          : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  return ctx_.own(space, H5Sclose, "create", "a dataspace");
}

H5Handle H5mdFile::string_type(std::size_t size) const {
  H5Handle type = ctx_.own(H5Tcopy(H5T_C_S1), H5Tclose, "create", "a string type");
  ctx_.check(H5Tset_size(type.get(), size), "size", "a string type");
  return type;
}

void H5mdFile::create_group(const char* name) const {
  ctx_.own(H5Gcreate2(file_.get(), name, link_props_.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           "create", name);
}

void H5mdFile::write_attribute(const char* object, const char* name, hid_t type, hid_t space,
                               const void* data) const {
  const std::string what = std::string(object) + " attribute " + name;
  // An attribute cannot change its size, so a new value (the status) replaces the old one.
  if (H5Aexists_by_name(file_.get(), object, name, H5P_DEFAULT) > 0) {
    ctx_.check(H5Adelete_by_name(file_.get(), object, name, H5P_DEFAULT), "replace", what);
  }
  const H5Handle attribute = ctx_.own(H5Acreate_by_name(file_.get(), object, name, type, space,
                                                        H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                      H5Aclose, "create", what);
  ctx_.check(H5Awrite(attribute.get(), type, data), "write", what);
}

void H5mdFile::write_string_attribute(const char* object, const char* name,
                                      const std::string& value) const {
  write_attribute(object, name, string_type(value.size() + 1).get(), dataspace({}).get(),
                  value.c_str());
}

H5mdFile::Dataset H5mdFile::create_series(std::string name, hid_t type,
                                          const std::vector<hsize_t>& row_shape,
                                          const void* fill) const {
  std::vector<hsize_t> extent = {0};
  std::vector<hsize_t> max = {H5S_UNLIMITED};
  std::vector<hsize_t> chunk = {row_shape.empty() ? kChunkRows : 1};
  for (hsize_t width : row_shape) {
    extent.push_back(width);
    max.push_back(width);
    chunk.push_back(std::min(width, kChunkGrains));
  }
  const int rank = static_cast<int>(extent.size());
  const H5Handle space = ctx_.own(H5Screate_simple(rank, extent.data(), max.data()), H5Sclose,
                                  "create the dataspace of", name);
  const H5Handle props =
      ctx_.own(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create the properties of", name);
  ctx_.check(H5Pset_chunk(props.get(), rank, chunk.data()), "chunk", name);
  if (fill != nullptr) {
    ctx_.check(H5Pset_fill_value(props.get(), type, fill), "set the fill value of", name);
  }
  H5Handle set = ctx_.own(H5Dcreate2(file_.get(), name.c_str(), type, space.get(),
                                     link_props_.get(), props.get(), H5P_DEFAULT),
                          H5Dclose, "create", name);
  return {std::move(set), std::move(name), std::move(extent)};
}

void H5mdFile::share_step_and_time(const std::string& from, const std::string& to) const {
  for (const char* leaf : {"/step", "/time"}) {
    const std::string target = to + leaf;
    ctx_.check(H5Lcreate_hard(file_.get(), (from + leaf).c_str(), file_.get(), target.c_str(),
                              link_props_.get(), H5P_DEFAULT),
               "link", target);
  }
}

// Grows `set` by one row and writes `data` into its first `valid` grains (the whole row of a
// scalar series); the rest of the row keeps the fill value.
void H5mdFile::append(Dataset& set, hsize_t valid, hid_t type, const void* data) {
  std::vector<hsize_t> start(set.extent.size(), 0);
  std::vector<hsize_t> count = set.extent;
  start[0] = set.extent[0];
  count[0] = 1;
  if (count.size() > 1) count[1] = valid;
  ++set.extent[0];
  ctx_.check(H5Dset_extent(set.handle.get(), set.extent.data()), "extend", set.name);
  if (valid == 0) return;  // a frame without grains is all fill values
  const H5Handle file_space =
      ctx_.own(H5Dget_space(set.handle.get()), H5Sclose, "get the dataspace of", set.name);
  ctx_.check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                 count.data(), nullptr),
             "select a row of", set.name);
  ctx_.check(
      H5Dwrite(set.handle.get(), type, dataspace(count).get(), file_space.get(), H5P_DEFAULT, data),
      "write", set.name);
}

void H5mdFile::require_open() const {
  if (file_.get() < 0) {
    throw std::logic_error("H5mdWriter: '" + ctx_.file().string() +
                           "' was already finished or abandoned");
  }
}

void H5mdFile::close() {
  sets_ = Datasets{};  // HDF5 keeps a file open while objects in it are open
  ctx_.check(file_.reset(), "close", "the file");
}

}  // namespace detail

template <int D>
H5mdWriter<D>::H5mdWriter(std::filesystem::path path, const RunMetadata& meta,
                          std::size_t max_grains)
    : file_(std::make_unique<detail::H5mdFile>(std::move(path), meta, D, max_grains)) {}

template <int D>
H5mdWriter<D>::H5mdWriter(std::filesystem::path path, Resume)
    : file_(std::make_unique<detail::H5mdFile>(std::move(path), D)) {}

template <int D>
void H5mdWriter<D>::write_checkpoint(const StateArchive& archive) {
  file_->write_checkpoint(archive);
}

template <int D>
void H5mdWriter<D>::replace_scene(const std::string& scene_ini) {
  file_->replace_scene(scene_ini);
}

template <int D>
H5mdWriter<D>::~H5mdWriter() = default;

template <int D>
void H5mdWriter<D>::write_frame(std::int64_t step, double time, const Particles<D>& particles) {
  const auto ids = particles.id();
  std::vector<std::size_t> order(ids.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
  detail::H5mdFile::FrameRows rows;
  for (std::size_t k : order) {
    const Vec<D>& x = particles.position()[k];
    const Vec<D>& v = particles.velocity()[k];
    rows.id.push_back(ids[k]);
    rows.position.insert(rows.position.end(), x.data(), x.data() + D);
    rows.velocity.insert(rows.velocity.end(), v.data(), v.data() + D);
    rows.radius.push_back(particles.radius()[k]);
  }
  file_->write_frame(step, time, rows);
}

template <int D>
void H5mdWriter<D>::write_observables(std::int64_t step, double time, const Observables& obs) {
  file_->write_observables(step, time, obs);
}

template <int D>
std::filesystem::path H5mdWriter<D>::complete() {
  return file_->complete();
}

template <int D>
void H5mdWriter<D>::publish() {
  file_->publish();
}

template <int D>
void H5mdWriter<D>::finish() {
  complete();
  publish();
}

template <int D>
std::filesystem::path H5mdWriter<D>::abandon(const std::string& reason) {
  return file_->abandon(reason);
}

template class H5mdWriter<2>;
template class H5mdWriter<3>;

}  // namespace granjet::analysis
