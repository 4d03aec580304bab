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

#include "analysis/checkpoint_file.hpp"
#include "analysis/file_lock.hpp"
#include "analysis/hdf5_copy.hpp"
#include "analysis/hdf5_handle.hpp"
#include "analysis/xdmf_sidecar.hpp"
#include "core/plate_face.hpp"

namespace granjet::analysis {
namespace {

// Grains per chunk along the grain axis: large enough for efficient I/O, small enough that the
// chunks beyond a shrunken grain count are never allocated.
constexpr hsize_t kChunkGrains = 16384;
// Contacts per chunk along the contact axis, which grows with the most contacts of a frame.
constexpr hsize_t kChunkContacts = 4096;
// Rows per chunk of the scalar time series (step, time, observables).
constexpr hsize_t kChunkRows = 1024;

constexpr const char* kScene = "/parameters/granjet/scene";
constexpr const char* kRequestedScene = "/parameters/granjet/requested_scene";

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
  // A stretch of a frame's rows, ids first..first+count-1: each grain in the row of its id
  // (fill values in the rows of grains not there), and the ids there, ascending.
  struct GrainRows {
    std::vector<GrainId> id;       // [count]
    std::vector<GrainId> present;  // ascending
    std::vector<double> position;  // row-major [count][dimension]
    std::vector<double> velocity;
    std::vector<double> radius;
    std::vector<double> omega;  // [count][spin width], when stored
    std::vector<double> force;  // [count][dimension], when stored
  };
  // A frame's touching pairs, when stored.
  struct ContactRows {
    std::vector<GrainId> pairs;                          // [contacts][2]
    std::vector<double> normal_force, tangential_force;  // [contacts][dimension]
    std::vector<double> overlap;                         // [contacts]
  };

  H5mdFile(std::filesystem::path path, const RunMetadata& meta, int dimension,
           std::size_t max_grains);
  // Reopens a run's .partial at its checkpoint (checkpoint_file.hpp): frames and observables
  // written after it are dropped, and the status is "running" again.
  H5mdFile(std::filesystem::path path, int dimension);
  void write_checkpoint(StateArchive archive, const ShareOfRank& share_of);
  void replace_scenes(const std::string& scene_ini, const std::string& requested_scene_ini);
  // A frame: begin_frame(), its rows in ascending stretches and its contacts in pieces, in
  // order, end_frame().
  void begin_frame();
  void write_grains(hsize_t first, hsize_t count, const GrainRows& rows);
  // The frame's next contacts, after those written so far.
  void write_contacts(const ContactRows& rows);
  // Where a frame's stretches are made ready, kept from frame to frame: fresh pages for each
  // cost more than filling them.
  GrainRows& stretch() { return stretch_; }
  // Returns the frame's grain count.
  std::size_t end_frame(std::int64_t step, double time);
  // Drops what a frame that failed half-way wrote: the file holds the frames before it.
  void drop_frame();
  std::size_t rows() const { return max_grains_; }
  // Which optional per-frame data the file stores.
  struct Content {
    bool omega, force, contacts;
  };
  Content content() const {
    return {sets_.omega.has_value(), sets_.force.has_value(), sets_.pairs.has_value()};
  }
  void write_observables(std::int64_t step, double time, const Observables& obs);
  std::filesystem::path complete();
  void publish();
  std::filesystem::path abandon(const std::string& reason);

 private:
  void drop_fields_and_analysis();
  // An extendable dataset; extent is its current shape [rows, row shape...].
  struct Dataset {
    H5Handle handle;
    std::string name;
    std::vector<hsize_t> extent;
  };
  struct Datasets {
    Dataset frame_step, frame_time, frame_grains, frame_contacts, dt, position, velocity, radius,
        id, present;
    std::optional<Dataset> omega, force, box, pairs, normal_force, tangential_force, overlap;
    Dataset observable_step, observable_time, grains;
    std::array<Dataset, kEnergies.size()> energies;
    // Every series with one row per frame, for truncation on resume.
    std::vector<Dataset*> per_frame();
  };

  void create_group(const char* name) const;
  void write_attribute(const char* object, const char* name, hid_t type, hid_t space,
                       const void* data) const {
    ctx_.write_attribute(file_.get(), object, name, type, space, data);
  }
  void write_string_attribute(const char* object, const char* name,
                              const std::string& value) const {
    ctx_.write_string_attribute(file_.get(), object, name, value);
  }
  void write_string_dataset(const char* name, const std::string& value) const;
  Dataset create_series(std::string name, hid_t type, const std::vector<hsize_t>& row_shape,
                        const void* fill) const;
  // H5MD lets elements sampled together share one step and one time dataset.
  void share_step_and_time(const std::string& from, const std::string& to) const;
  void append(Dataset& set, hsize_t valid, hid_t type, const void* data);
  // Writes `count` grains from grain `first` on into the last row of `set`.
  void write_last_row(Dataset& set, hsize_t first, hsize_t count, hid_t type, const void* data);
  // Widens the second axis of `set` (the contacts of a frame) to at least `width`.
  void widen(Dataset& set, hsize_t width);
  void write_unit(const std::string& dataset, const char* quantity) const;
  void require_open() const;
  XdmfLayout layout() const {
    return {dimension_, max_grains_, sets_.omega.has_value(), sets_.force.has_value(),
            sets_.pairs ? sets_.pairs->extent[1] : 0};
  }
  void close();
  Dataset open_series(const std::string& name) const;
  // Whether `name` exists, with every group on the way.
  bool exists(const std::string& name) const;
  void read_all(const Dataset& set, hid_t type, void* out) const;
  void read_first_row(const Dataset& set, double* out) const;
  void truncate(Dataset& set, hsize_t rows);

  std::filesystem::path path_;
  H5Context ctx_;
  std::optional<FileLock> lock_;  // from before the .partial is truncated until it is renamed
  int dimension_;
  hsize_t max_grains_;
  UnitLabels units_ = UnitLabels::kMdAnalysis;
  H5Handle file_;  // declared before the datasets, so it is closed after them
  H5Handle link_props_;
  Datasets sets_;
  std::vector<XdmfFrame> frames_;
  // The frame being written: the grains present in it so far, and the first row not yet written.
  hsize_t frame_present_ = 0;
  hsize_t frame_rows_done_ = 0;
  hsize_t frame_contacts_ = 0;        // the frame's contacts written so far
  hsize_t contact_width_before_ = 0;  // the contact axis before the frame, for drop_frame
  GrainRows stretch_;
  std::vector<double> box_;      // periodic edges, stored with every frame
  double frame_interval_ = 1.0;  // the dt observable
};

// The unit attribute of `dataset` for `quantity`.
void H5mdFile::write_unit(const std::string& dataset, const char* quantity) const {
  struct Label {
    const char* quantity;
    const char* mdanalysis;  // MDAnalysis's base unit, standing for the reduced one at factor 1
    const char* reduced;     // H5MD unit string of the reduced unit
  };
  static constexpr std::array<Label, 6> kLabels = {{
      {"length", "Angstrom", "d"},
      {"time", "ps", "d u0-1"},
      {"velocity", "Angstrom ps-1", "u0"},
      {"angular velocity", "ps-1", "u0 d-1"},
      {"force", "kJ mol-1 Angstrom-1", "m u0+2 d-1"},
      {"energy", "kJ mol-1", "m u0+2"},
  }};
  for (const Label& label : kLabels)
    if (std::string_view(label.quantity) == quantity) {
      // Variable-length, unlike H5MD's fixed-length strings: h5py reads those as bytes, which
      // MDAnalysis does not recognise as a unit.
      const char* unit = units_ == UnitLabels::kReduced ? label.reduced : label.mdanalysis;
      const H5Handle type = ctx_.string_type(H5T_VARIABLE);
      write_attribute(dataset.c_str(), "unit", type.get(), ctx_.dataspace({}).get(), &unit);
      return;
    }
  throw std::logic_error(std::string("H5mdWriter: no unit for ") + quantity);
}

std::vector<H5mdFile::Dataset*> H5mdFile::Datasets::per_frame() {
  std::vector<Dataset*> sets = {&frame_step, &frame_time, &frame_grains, &frame_contacts,
                                &dt,         &position,   &velocity,     &radius,
                                &id,         &present};
  for (std::optional<Dataset>* set :
       {&omega, &force, &box, &pairs, &normal_force, &tangential_force, &overlap})
    if (set->has_value()) sets.push_back(&**set);
  return sets;
}

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
  // An earlier run's checkpoint would be resumed with this run's frames.
  remove_checkpoint_file(checkpoint_path(path_));
  file_ = ctx_.own(H5Fcreate(ctx_.file().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                   H5Fclose, "create", "the HDF5 file");
  // Missing parent groups are created on the way, so every object is made by its full path.
  link_props_ = ctx_.own(H5Pcreate(H5P_LINK_CREATE), H5Pclose, "create", "link properties");
  ctx_.check(H5Pset_create_intermediate_group(link_props_.get(), 1), "set", "link properties");

  create_group("/h5md/author");
  create_group("/h5md/creator");
  const std::array<int, 2> version = {1, 1};
  write_attribute("/h5md", "version", H5T_NATIVE_INT, ctx_.dataspace({2}).get(), version.data());
  write_string_attribute("/h5md/author", "name", meta.author);
  write_string_attribute("/h5md/creator", "name", meta.creator);
  write_string_attribute("/h5md/creator", "version", meta.creator_version);

  // H5MD's units module: the numbers are in reduced units whatever the labels say.
  create_group("/h5md/modules/units");
  const std::array<int, 2> units_version = {1, 0};
  write_attribute("/h5md/modules/units", "version", H5T_NATIVE_INT, ctx_.dataspace({2}).get(),
                  units_version.data());
  write_string_attribute("/h5md/modules/units", "system",
                         "granjet reduced: length d (grain diameter), velocity u0 (jet speed), "
                         "time d/u0, mass m (grain mass)");

  const bool periodic = !meta.periodic_box.empty();
  if (periodic && meta.periodic_box.size() != static_cast<std::size_t>(dimension_))
    throw std::invalid_argument("H5mdWriter: the periodic box needs one edge per dimension");
  create_group("/particles/all/box");
  write_attribute("/particles/all/box", "dimension", H5T_NATIVE_INT, ctx_.dataspace({}).get(),
                  &dimension_);
  std::string boundary;
  for (int d = 0; d < dimension_; ++d)
    boundary.append(periodic ? "periodic" : "none", 9);  // padded with NULs to 9
  write_attribute("/particles/all/box", "boundary", ctx_.string_type(9).get(),
                  ctx_.dataspace({static_cast<hsize_t>(dimension_)}).get(), boundary.data());

  // Rows of removed grains keep these fill values; -1 is H5MD's "no particle" id.
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
  sets_.present = create_series(all + "present/value", H5T_NATIVE_INT64, {g}, &no_grain);
  std::vector<std::string> per_frame = {all + "velocity", all + "radius", all + "id",
                                        all + "present"};
  if (meta.omega) {
    const std::vector<hsize_t> shape =
        dimension_ == 3 ? std::vector<hsize_t>{g, 3} : std::vector<hsize_t>{g};
    sets_.omega = create_series(all + "omega/value", H5T_NATIVE_DOUBLE, shape, &nan);
    per_frame.push_back(all + "omega");
  }
  if (meta.force) {
    sets_.force = create_series(all + "force/value", H5T_NATIVE_DOUBLE, {g, d}, &nan);
    per_frame.push_back(all + "force");
  }
  if (periodic) {
    // H5MD's triclinic form (a diagonal matrix for a cuboid), the one MDAnalysis reads.
    sets_.box = create_series(all + "box/edges/value", H5T_NATIVE_DOUBLE, {d, d}, nullptr);
    per_frame.push_back(all + "box/edges");
    box_ = meta.periodic_box;
  }
  const std::string obs = "/observables/";
  sets_.frame_grains = create_series(obs + "frame_grains/value", H5T_NATIVE_INT64, {}, nullptr);
  sets_.frame_contacts = create_series(obs + "frame_contacts/value", H5T_NATIVE_INT64, {}, nullptr);
  sets_.dt = create_series(obs + "dt/value", H5T_NATIVE_DOUBLE, {}, nullptr);
  frame_interval_ = meta.frame_interval;
  for (const char* name : {"frame_grains", "frame_contacts", "dt"}) per_frame.push_back(obs + name);
  if (meta.contacts) {
    // Pairs of ids of /particles/all (H5MD 1.1 tuples list); the width grows with the most
    // contacts any frame has.
    sets_.pairs =
        create_series("/connectivity/contacts/value", H5T_NATIVE_INT64, {0, 2}, &no_grain);
    hobj_ref_t group{};
    ctx_.check(H5Rcreate(&group, file_.get(), "/particles/all", H5R_OBJECT, -1), "reference",
               "/particles/all");
    write_attribute("/connectivity/contacts", "particles_group", H5T_STD_REF_OBJ,
                    ctx_.dataspace({}).get(), &group);
    sets_.normal_force =
        create_series("/contacts/normal_force/value", H5T_NATIVE_DOUBLE, {0, d}, &nan);
    sets_.tangential_force =
        create_series("/contacts/tangential_force/value", H5T_NATIVE_DOUBLE, {0, d}, &nan);
    sets_.overlap = create_series("/contacts/overlap/value", H5T_NATIVE_DOUBLE, {0}, &nan);
    for (const char* name : {"/connectivity/contacts", "/contacts/normal_force",
                             "/contacts/tangential_force", "/contacts/overlap"})
      per_frame.emplace_back(name);
  }
  for (const std::string& element : per_frame) share_step_and_time(all + "position", element);

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

  units_ = meta.unit_labels;
  for (const Dataset* set : {&sets_.position, &sets_.radius}) write_unit(set->name, "length");
  for (const Dataset* set : {&sets_.frame_time, &sets_.dt, &sets_.observable_time})
    write_unit(set->name, "time");
  write_unit(sets_.velocity.name, "velocity");
  for (const Dataset& set : sets_.energies) write_unit(set.name, "energy");
  if (sets_.box) write_unit(sets_.box->name, "length");
  if (sets_.omega) write_unit(sets_.omega->name, "angular velocity");
  if (sets_.force) write_unit(sets_.force->name, "force");
  if (sets_.overlap) write_unit(sets_.overlap->name, "length");
  for (const std::optional<Dataset>* set : {&sets_.normal_force, &sets_.tangential_force})
    if (*set) write_unit((*set)->name, "force");

  create_group("/parameters/granjet");
  write_string_attribute("/parameters/granjet", "backend", meta.backend);
  write_attribute("/parameters/granjet", "dimension", H5T_NATIVE_INT, ctx_.dataspace({}).get(),
                  &dimension_);
  write_string_attribute("/parameters/granjet", "status", "running");
  write_string_dataset(kScene, meta.scene_ini);
  if (!meta.requested_scene_ini.empty())
    write_string_dataset(kRequestedScene, meta.requested_scene_ini);
  if (!meta.members.empty()) {
    std::string lines;
    for (const std::string& member : meta.members) lines += member + "\n";
    write_string_dataset("/parameters/granjet/members", lines);
  }
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
}

// A dataset, not an attribute: the scene may exceed the 64 KiB attribute limit.
void H5mdFile::write_string_dataset(const char* name, const std::string& value) const {
  const H5Handle type = ctx_.string_type(value.size() + 1);
  const H5Handle set = ctx_.own(H5Dcreate2(file_.get(), name, type.get(), ctx_.dataspace({}).get(),
                                           link_props_.get(), H5P_DEFAULT, H5P_DEFAULT),
                                H5Dclose, "create", name);
  ctx_.check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()), "write",
             name);
}

H5mdFile::H5mdFile(std::filesystem::path path, int dimension)
    : path_(std::move(path)), ctx_(partial_path(path_)), dimension_(dimension) {
  lock_.emplace(ctx_.file());
  // The root's entries alone: the writer's counts, not the grains.
  const StateArchive checkpoint = read_checkpoint_file(checkpoint_path(path_), {0, 0});
  drop_fields_and_analysis();
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
  sets_.present = open_series(all + "present/value");
  sets_.frame_grains = open_series(obs + "frame_grains/value");
  sets_.frame_contacts = open_series(obs + "frame_contacts/value");
  sets_.dt = open_series(obs + "dt/value");
  const auto optional = [&](std::optional<Dataset>& set, const std::string& name) {
    if (exists(name)) set = open_series(name);
  };
  optional(sets_.omega, all + "omega/value");
  optional(sets_.force, all + "force/value");
  optional(sets_.box, all + "box/edges/value");
  optional(sets_.pairs, "/connectivity/contacts/value");
  optional(sets_.normal_force, "/contacts/normal_force/value");
  optional(sets_.tangential_force, "/contacts/tangential_force/value");
  optional(sets_.overlap, "/contacts/overlap/value");
  sets_.observable_step = open_series(obs + kEnergies[0] + "/step");
  sets_.observable_time = open_series(obs + kEnergies[0] + "/time");
  for (std::size_t k = 0; k < kEnergies.size(); ++k)
    sets_.energies[k] = open_series(obs + kEnergies[k] + "/value");
  sets_.grains = open_series(obs + "grains/value");
  max_grains_ = sets_.position.extent.at(1);
  const auto frames = static_cast<hsize_t>(checkpoint.integer("writer/frames"));
  const auto rows = static_cast<hsize_t>(checkpoint.integer("writer/observable_rows"));
  // Truncation that lengthened a dataset would make up rows: every one must hold the
  // checkpoint's (it flushed them before it was written).
  const auto keep = [&](Dataset& set, hsize_t count) {
    if (count > set.extent[0])
      ctx_.fail("resume at", "a checkpoint that counts more rows than " + set.name + " holds");
    truncate(set, count);
  };
  for (Dataset* set : sets_.per_frame()) keep(*set, frames);
  for (Dataset* set : {&sets_.observable_step, &sets_.observable_time, &sets_.grains})
    keep(*set, rows);
  for (Dataset& set : sets_.energies) keep(set, rows);
  std::vector<double> time(frames), interval(frames);
  std::vector<std::int64_t> grains(frames), contacts(frames);
  if (frames > 0) {
    read_all(sets_.frame_time, H5T_NATIVE_DOUBLE, time.data());
    read_all(sets_.dt, H5T_NATIVE_DOUBLE, interval.data());
    read_all(sets_.frame_grains, H5T_NATIVE_INT64, grains.data());
    read_all(sets_.frame_contacts, H5T_NATIVE_INT64, contacts.data());
    frame_interval_ = interval[0];
  }
  if (sets_.box) {
    if (frames == 0) ctx_.fail("resume at", "a checkpoint before the first frame");
    std::vector<double> edges(dimension_ * dimension_);
    read_first_row(*sets_.box, edges.data());
    for (int k = 0; k < dimension_; ++k) box_.push_back(edges[k * (dimension_ + 1)]);
  }
  for (hsize_t k = 0; k < frames; ++k)
    frames_.push_back(
        {time[k], static_cast<std::size_t>(grains[k]), static_cast<std::size_t>(contacts[k])});
  write_string_attribute("/parameters/granjet", "status", "running");
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
}

void H5mdFile::replace_scenes(const std::string& scene_ini,
                              const std::string& requested_scene_ini) {
  require_open();
  for (const char* name : {kScene, kRequestedScene})
    if (exists(name)) ctx_.check(H5Ldelete(file_.get(), name, H5P_DEFAULT), "replace", name);
  write_string_dataset(kScene, scene_ini);
  if (!requested_scene_ini.empty()) write_string_dataset(kRequestedScene, requested_scene_ini);
}

// Killed after it completed, while it stored its fields and analysis: the resume makes them
// again, and a kill in the middle of that can leave a header half-written, which HDF5 cannot
// delete. The file is copied without them (hdf5_copy.hpp, which never opens what it leaves
// out), under the same lock.
void H5mdFile::drop_fields_and_analysis() {
  bool stored = false;
  {
    const H5Handle file = ctx_.open_read_only();
    for (const char* group : {"/fields", "/analysis"})
      stored = stored || H5Lexists(file.get(), group, H5P_DEFAULT) > 0;
  }
  if (!stored) return;
  std::filesystem::path copy = ctx_.file();
  copy += ".copy";
  FileLock held(copy);
  try {
    copy_hdf5_except(ctx_.file(), copy, {"fields", "analysis"});
    std::filesystem::rename(copy, ctx_.file());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(copy, ignored);
    throw;
  }
  lock_.reset();
  lock_.emplace(std::move(held));
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

bool H5mdFile::exists(const std::string& name) const {
  for (std::size_t slash = name.find('/', 1);; slash = name.find('/', slash + 1)) {
    if (H5Lexists(file_.get(), name.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
  }
}

void H5mdFile::read_all(const Dataset& set, hid_t type, void* out) const {
  ctx_.check(H5Dread(set.handle.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out), "read", set.name);
}

void H5mdFile::read_first_row(const Dataset& set, double* out) const {
  std::vector<hsize_t> start(set.extent.size(), 0), count = set.extent;
  count[0] = 1;
  const H5Handle file_space = ctx_.own(H5Dget_space(set.handle.get()), H5Sclose, "query", set.name);
  ctx_.check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                 count.data(), nullptr),
             "select a row of", set.name);
  ctx_.check(H5Dread(set.handle.get(), H5T_NATIVE_DOUBLE, ctx_.dataspace(count).get(),
                     file_space.get(), H5P_DEFAULT, out),
             "read", set.name);
}

void H5mdFile::truncate(Dataset& set, hsize_t rows) {
  set.extent[0] = rows;
  ctx_.check(H5Dset_extent(set.handle.get(), set.extent.data()), "truncate", set.name);
}

// The checkpoint counts the frames and observables written so far, so that a resume drops those
// written after it; they are on disk before it is.
void H5mdFile::write_checkpoint(StateArchive archive, const ShareOfRank& share_of) {
  require_open();
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
  archive.put("writer/frames", static_cast<std::int64_t>(sets_.frame_step.extent[0]));
  archive.put("writer/observable_rows", static_cast<std::int64_t>(sets_.observable_step.extent[0]));
  write_checkpoint_file(checkpoint_path(path_), archive, share_of);
}

// Every per-grain series gets a row of fill values, which the frame's stretches then fill.
void H5mdFile::begin_frame() {
  require_open();
  for (Dataset* set : {&sets_.position, &sets_.velocity, &sets_.radius, &sets_.id, &sets_.present})
    append(*set, 0, H5T_NATIVE_DOUBLE, nullptr);
  for (std::optional<Dataset>* set : {&sets_.omega, &sets_.force, &sets_.pairs, &sets_.normal_force,
                                      &sets_.tangential_force, &sets_.overlap})
    if (*set) append(**set, 0, H5T_NATIVE_DOUBLE, nullptr);
  frame_present_ = 0;
  frame_rows_done_ = 0;
  frame_contacts_ = 0;
  contact_width_before_ = sets_.pairs ? sets_.pairs->extent[1] : 0;
}

void H5mdFile::write_grains(hsize_t first, hsize_t count, const GrainRows& rows) {
  require_open();
  if (first < frame_rows_done_ || first + count > max_grains_)
    throw std::logic_error("H5mdWriter: rows " + std::to_string(first) + ".." +
                           std::to_string(first + count) + " of a frame come out of order");
  frame_rows_done_ = first + count;
  write_last_row(sets_.position, first, count, H5T_NATIVE_DOUBLE, rows.position.data());
  write_last_row(sets_.velocity, first, count, H5T_NATIVE_DOUBLE, rows.velocity.data());
  write_last_row(sets_.radius, first, count, H5T_NATIVE_DOUBLE, rows.radius.data());
  write_last_row(sets_.id, first, count, H5T_NATIVE_INT64, rows.id.data());
  if (sets_.omega) write_last_row(*sets_.omega, first, count, H5T_NATIVE_DOUBLE, rows.omega.data());
  if (sets_.force) write_last_row(*sets_.force, first, count, H5T_NATIVE_DOUBLE, rows.force.data());
  write_last_row(sets_.present, frame_present_, rows.present.size(), H5T_NATIVE_INT64,
                 rows.present.data());
  frame_present_ += rows.present.size();
}

// The contact axis grows with the most contacts of a frame so far, piece by piece: no more of
// a frame's contacts need be held at once than a piece.
void H5mdFile::write_contacts(const ContactRows& rows) {
  require_open();
  if (!sets_.pairs) throw std::logic_error("H5mdWriter: this file stores no contacts");
  const hsize_t count = rows.overlap.size();
  for (Dataset* set :
       {&*sets_.pairs, &*sets_.normal_force, &*sets_.tangential_force, &*sets_.overlap})
    widen(*set, frame_contacts_ + count);
  write_last_row(*sets_.pairs, frame_contacts_, count, H5T_NATIVE_INT64, rows.pairs.data());
  write_last_row(*sets_.normal_force, frame_contacts_, count, H5T_NATIVE_DOUBLE,
                 rows.normal_force.data());
  write_last_row(*sets_.tangential_force, frame_contacts_, count, H5T_NATIVE_DOUBLE,
                 rows.tangential_force.data());
  write_last_row(*sets_.overlap, frame_contacts_, count, H5T_NATIVE_DOUBLE, rows.overlap.data());
  frame_contacts_ += count;
}

std::size_t H5mdFile::end_frame(std::int64_t step, double time) {
  require_open();
  const hsize_t contacts = frame_contacts_;
  const auto grains = static_cast<std::int64_t>(frame_present_);
  const auto contact_count = static_cast<std::int64_t>(contacts);
  append(sets_.frame_step, 1, H5T_NATIVE_INT64, &step);
  append(sets_.frame_time, 1, H5T_NATIVE_DOUBLE, &time);
  append(sets_.frame_grains, 1, H5T_NATIVE_INT64, &grains);
  append(sets_.frame_contacts, 1, H5T_NATIVE_INT64, &contact_count);
  append(sets_.dt, 1, H5T_NATIVE_DOUBLE, &frame_interval_);
  if (sets_.box) {
    std::vector<double> edges(dimension_ * dimension_, 0.0);
    for (int k = 0; k < dimension_; ++k) edges[k * (dimension_ + 1)] = box_[k];
    append(*sets_.box, dimension_, H5T_NATIVE_DOUBLE, edges.data());
  }
  // A run killed later still leaves this frame readable.
  ctx_.check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "flush", "the file");
  frames_.push_back({time, frame_present_, contacts});
  return frame_present_;
}

void H5mdFile::drop_frame() {
  require_open();
  const hsize_t frames = sets_.frame_step.extent[0];
  for (Dataset* set : sets_.per_frame())
    if (set->extent[0] > frames) truncate(*set, frames);
  if (sets_.pairs)  // nor its contacts' width
    for (Dataset* set :
         {&*sets_.pairs, &*sets_.normal_force, &*sets_.tangential_force, &*sets_.overlap})
      if (set->extent[1] > contact_width_before_) {
        set->extent[1] = contact_width_before_;
        ctx_.check(H5Dset_extent(set->handle.get(), set->extent.data()), "narrow", set->name);
      }
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
  write_string_attribute("/parameters/granjet", "status", "complete");
  const XdmfLayout sidecar = layout();
  close();
  // An ensemble file holds no frames: nothing to draw, and a sidecar of frames that an earlier
  // file of this name held would show what is gone.
  if (frames_.empty())
    std::filesystem::remove(xdmf_path_for(path_));
  else
    write_xdmf_sidecar(xdmf_path_for(path_), path_.filename().string(), sidecar, frames_);
  return ctx_.file();
}

// A complete run resumes nothing: its checkpoint goes once the file has its final name.
void H5mdFile::publish() {
  std::filesystem::rename(ctx_.file(), path_);
  remove_checkpoint_file(checkpoint_path(path_));
  lock_.reset();
}

std::filesystem::path H5mdFile::abandon(const std::string& reason) {
  require_open();
  write_string_attribute("/parameters/granjet", "status", reason);
  close();
  return ctx_.file();
}

void H5mdFile::create_group(const char* name) const {
  ctx_.own(H5Gcreate2(file_.get(), name, link_props_.get(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
           "create", name);
}

H5mdFile::Dataset H5mdFile::create_series(std::string name, hid_t type,
                                          const std::vector<hsize_t>& row_shape,
                                          const void* fill) const {
  std::vector<hsize_t> extent = {0};
  std::vector<hsize_t> max = {H5S_UNLIMITED};
  std::vector<hsize_t> chunk = {row_shape.empty() ? kChunkRows : 1};
  for (hsize_t width : row_shape) {
    extent.push_back(width);
    // Width 0: the axis grows (widen) with the data, the contacts of a frame.
    max.push_back(width == 0 ? H5S_UNLIMITED : width);
    chunk.push_back(width == 0 ? kChunkContacts : std::min(width, kChunkGrains));
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

void H5mdFile::widen(Dataset& set, hsize_t width) {
  if (set.extent[1] >= width) return;
  set.extent[1] = width;
  ctx_.check(H5Dset_extent(set.handle.get(), set.extent.data()), "widen", set.name);
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
  ++set.extent[0];
  ctx_.check(H5Dset_extent(set.handle.get(), set.extent.data()), "extend", set.name);
  write_last_row(set, 0, set.extent.size() > 1 ? valid : 1, type, data);
}

void H5mdFile::write_last_row(Dataset& set, hsize_t first, hsize_t count, hid_t type,
                              const void* data) {
  if (count == 0) return;  // the rows keep their fill values
  std::vector<hsize_t> start(set.extent.size(), 0);
  std::vector<hsize_t> shape = set.extent;
  start[0] = set.extent[0] - 1;
  shape[0] = 1;
  if (shape.size() > 1) {
    start[1] = first;
    shape[1] = count;
  }
  const H5Handle file_space =
      ctx_.own(H5Dget_space(set.handle.get()), H5Sclose, "get the dataspace of", set.name);
  ctx_.check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                 shape.data(), nullptr),
             "select a row of", set.name);
  ctx_.check(H5Dwrite(set.handle.get(), type, ctx_.dataspace(shape).get(), file_space.get(),
                      H5P_DEFAULT, data),
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
void H5mdWriter<D>::write_checkpoint(const StateArchive& archive, const ShareOfRank& share_of) {
  file_->write_checkpoint(archive, share_of);
}

template <int D>
void H5mdWriter<D>::replace_scenes(const std::string& scene_ini,
                                   const std::string& requested_scene_ini) {
  file_->replace_scenes(scene_ini, requested_scene_ini);
}

template <int D>
H5mdWriter<D>::~H5mdWriter() = default;

namespace {

// A frame's grains and contacts as the file's rows, one stretch of ids at a time.
template <int D>
class FrameRowsSink final : public FrameSink<D> {
 public:
  FrameRowsSink(detail::H5mdFile& file, detail::H5mdFile::GrainRows& rows)
      : file_(file), content_(file.content()), rows_(rows) {}

  void grains(GrainId first, GrainId end, const Particles<D>& grains,
              std::span<const Vec<D>> force) override {
    const auto rows = static_cast<GrainId>(file_.rows());
    const std::size_t count = static_cast<std::size_t>(end - first);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    constexpr std::size_t kSpin = D == 3 ? 3 : 1;
    if (content_.force && force.size() != grains.size())
      throw std::logic_error("H5mdWriter: this file stores forces; the frame has none");
    detail::H5mdFile::GrainRows& f = rows_;
    f.id.assign(count, -1);
    f.present.clear();
    f.position.assign(count * D, nan);
    f.velocity.assign(count * D, nan);
    f.radius.assign(count, nan);
    f.omega.assign(content_.omega ? count * kSpin : 0, nan);
    f.force.assign(content_.force ? count * D : 0, nan);
    const auto ids = grains.id();
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const GrainId id = ids[k];
      if (id < 0 || id >= rows)
        throw std::invalid_argument("H5mdWriter: grain id " + std::to_string(id) +
                                    " has no row (ids 0.." + std::to_string(rows - 1) + ")");
      if (id < first || id >= end)
        throw std::logic_error("H5mdWriter: grain id " + std::to_string(id) +
                               " came with the rows " + std::to_string(first) + ".." +
                               std::to_string(end - 1));
      const auto r = static_cast<std::size_t>(id - first);
      f.id[r] = id;
      std::copy_n(grains.position()[k].data(), D, &f.position[r * D]);
      std::copy_n(grains.velocity()[k].data(), D, &f.velocity[r * D]);
      f.radius[r] = grains.radius()[k];
      if (content_.omega) {
        if constexpr (D == 3)
          std::copy_n(grains.spin()[k].data(), 3, &f.omega[r * 3]);
        else
          f.omega[r] = grains.spin()[k];
      }
      if (content_.force) std::copy_n(force[k].data(), D, &f.force[r * D]);
    }
    for (std::size_t r = 0; r < count; ++r)
      if (f.id[r] >= 0) f.present.push_back(f.id[r]);
    file_.write_grains(static_cast<hsize_t>(first), count, f);
  }

  // Each piece is written as it comes.
  void contacts(std::span<const typename ForceSample<D>::Contact> contacts) override {
    if (!content_.contacts) return;
    detail::H5mdFile::ContactRows& rows = contacts_;
    rows.pairs.clear();
    rows.normal_force.clear();
    rows.tangential_force.clear();
    rows.overlap.clear();
    // Pairs only: a contact with the plate (j = kPlateId) has no partner row to draw.
    for (const auto& c : contacts) {
      if (c.j == kPlateId) continue;
      rows.pairs.insert(rows.pairs.end(), {c.i, c.j});
      rows.normal_force.insert(rows.normal_force.end(), c.normal_force.data(),
                               c.normal_force.data() + D);
      rows.tangential_force.insert(rows.tangential_force.end(), c.tangential_force.data(),
                                   c.tangential_force.data() + D);
      rows.overlap.push_back(c.overlap);
    }
    file_.write_contacts(rows);
  }

 private:
  detail::H5mdFile& file_;
  detail::H5mdFile::Content content_;
  detail::H5mdFile::GrainRows& rows_;       // one stretch's
  detail::H5mdFile::ContactRows contacts_;  // one piece's
};

}  // namespace

template <int D>
void H5mdWriter<D>::write_frame(std::int64_t step, double time, const Particles<D>& particles,
                                const ForceSample<D>* forces) {
  const auto content = file_->content();
  if ((content.force || content.contacts) && forces == nullptr)
    throw std::logic_error("H5mdWriter: this file stores forces; write_frame needs them");
  write_frame(step, time, [&](FrameSink<D>& sink) {
    sink.grains(0, static_cast<GrainId>(file_->rows()), particles,
                content.force ? std::span<const Vec<D>>(forces->total) : std::span<const Vec<D>>());
    if (content.contacts) sink.contacts(forces->contacts);
  });
}

template <int D>
std::size_t H5mdWriter<D>::write_frame(std::int64_t step, double time, const Simulator<D>& sim,
                                       std::size_t block_rows) {
  const auto content = file_->content();
  return write_frame(step, time, [&](FrameSink<D>& sink) {
    sim.frame({file_->rows(), block_rows, content.force, content.contacts}, sink);
  });
}

template <int D>
std::size_t H5mdWriter<D>::write_frame(std::int64_t step, double time,
                                       const std::function<void(FrameSink<D>&)>& fill) {
  FrameRowsSink<D> sink(*file_, file_->stretch());
  file_->begin_frame();
  try {
    fill(sink);
  } catch (...) {
    file_->drop_frame();
    throw;
  }
  return file_->end_frame(step, time);
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
