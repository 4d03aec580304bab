// The H5MD layout as other readers (h5py, MDAnalysis, ParaView) see it, read with HDF5 itself:
// a row per grain id over the whole run, fill values for removed grains, the present list, the
// unit attributes, the periodic box, dt, and the opt-in omega, force and contacts.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "analysis/h5md_writer.hpp"
#include "core/plate_face.hpp"
#include "../common/hdf5_text.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

// Grains 0..5; grain 2 leaves after frame 0, grain 4 after frame 1.
const std::vector<std::vector<GrainId>> kFrames = {
    {5, 0, 2, 4, 1, 3}, {0, 1, 3, 4, 5}, {3, 5, 0, 1}};
constexpr std::size_t kRows = 6;

Vec<3> position_of(GrainId id, int frame) { return Vec<3>(id, 0.5 * frame, -1.0 * id); }

Particles<3> grains_of(int frame) {
  Particles<3> p;
  for (GrainId id : kFrames[frame]) {
    p.add(id, GrainKind::kFree, position_of(id, frame), Vec<3>(0.0, 0.0, -1.0 - frame), 0.5, 1.0);
    p.spin().back() = Vec<3>(0.1 * id, 0.0, frame);
  }
  return p;
}

// The contacts of frame k: k + 1 pairs (so the contact axis grows, then shrinks to 0 at the
// end), and one with the plate, which has no partner row.
ForceSample<3> forces_of(int frame, const Particles<3>& p) {
  ForceSample<3> f;
  f.total.assign(p.size(), Vec<3>::Zero());
  for (std::size_t k = 0; k < p.size(); ++k) f.total[k] = Vec<3>(p.id()[k], 1.0, 2.0);
  const int pairs = frame == 2 ? 0 : frame + 1;
  for (int c = 0; c < pairs; ++c)
    f.contacts.push_back(
        {p.id()[c], p.id()[c + 1], Vec<3>(0, 0, c + 1.0), Vec<3>(0.5, 0, 0), 0.01 * (c + 1)});
  f.contacts.push_back({p.id()[0], kPlateId, Vec<3>(0, 0, 9.0), Vec<3>::Zero(), 0.02});
  return f;
}

class H5File {
 public:
  explicit H5File(const fs::path& file) : id_(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {}
  ~H5File() { H5Fclose(id_); }
  bool exists(const std::string& name) const {
    for (std::size_t slash = name.find('/', 1);; slash = name.find('/', slash + 1)) {
      if (H5Lexists(id_, name.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return false;
      if (slash == std::string::npos) return true;
    }
  }
  std::vector<hsize_t> shape(const std::string& name) const {
    const hid_t set = H5Dopen2(id_, name.c_str(), H5P_DEFAULT);
    const hid_t space = H5Dget_space(set);
    std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    H5Sclose(space);
    H5Dclose(set);
    return dims;
  }
  template <class T>
  std::vector<T> values(const std::string& name) const {
    std::size_t n = 1;
    for (hsize_t d : shape(name)) n *= d;
    std::vector<T> out(n);
    const hid_t set = H5Dopen2(id_, name.c_str(), H5P_DEFAULT);
    H5Dread(set, std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64, H5S_ALL, H5S_ALL,
            H5P_DEFAULT, out.data());
    H5Dclose(set);
    return out;
  }
  // A string attribute (the unit attributes are variable-length).
  std::string text_attribute(const std::string& object, const char* name) const {
    return testing::string_attribute(id_, object, name);
  }
  std::vector<std::string> fixed_strings(const std::string& object, const char* name) const {
    const hid_t a = H5Aopen_by_name(id_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t type = H5Aget_type(a), space = H5Aget_space(a);
    const std::size_t width = H5Tget_size(type);
    const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space));
    std::string packed(width * n, '\0');
    H5Aread(a, type, packed.data());
    std::vector<std::string> out;
    for (std::size_t k = 0; k < n; ++k) out.emplace_back(packed.substr(k * width, width).c_str());
    H5Sclose(space);
    H5Tclose(type);
    H5Aclose(a);
    return out;
  }

 private:
  hid_t id_;
};

class H5mdLayout : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("granjet_layout_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(RunMetadata meta) {
    const fs::path file = dir_ / "run.h5";
    H5mdWriter<3> writer(file, meta, kRows);
    for (int k = 0; k < 3; ++k) {
      const Particles<3> p = grains_of(k);
      const ForceSample<3> f = forces_of(k, p);
      writer.write_frame(10 * k, 0.5 * k, p, &f);
      writer.write_observables(10 * k, 0.5 * k, {});
    }
    writer.finish();
    return file;
  }

  fs::path dir_;
};

RunMetadata metadata() {
  RunMetadata meta;
  meta.backend = "soft_dem";
  meta.dimension = 3;
  meta.frame_interval = 0.5;
  return meta;
}

TEST_F(H5mdLayout, EachGrainKeepsItsRowAndRemovedGrainsKeepFillValues) {
  const H5File f(write(metadata()));
  const std::string all = "/particles/all/";
  const auto id = f.values<std::int64_t>(all + "id/value");
  const auto present = f.values<std::int64_t>(all + "present/value");
  const auto x = f.values<double>(all + "position/value");
  const auto r = f.values<double>(all + "radius/value");
  ASSERT_EQ(f.shape(all + "position/value"), (std::vector<hsize_t>{3, kRows, 3}));
  for (int k = 0; k < 3; ++k)
    for (GrainId g = 0; g < static_cast<GrainId>(kRows); ++g) {
      SCOPED_TRACE("frame " + std::to_string(k) + ", grain " + std::to_string(g));
      const bool here = std::count(kFrames[k].begin(), kFrames[k].end(), g) > 0;
      const std::size_t row = k * kRows + g;
      EXPECT_EQ(id[row], here ? g : -1);
      for (int a = 0; a < 3; ++a)
        if (here)
          EXPECT_EQ(x[row * 3 + a], position_of(g, k)[a]);
        else
          EXPECT_TRUE(std::isnan(x[row * 3 + a]));
      EXPECT_EQ(std::isnan(r[row]), !here);
    }
  // The present rows, ascending, then H5MD's fill -1.
  EXPECT_EQ(std::vector<std::int64_t>(present.begin() + 2 * kRows, present.end()),
            (std::vector<std::int64_t>{0, 1, 3, 5, -1, -1}));
  EXPECT_EQ(f.values<std::int64_t>("/observables/frame_grains/value"),
            (std::vector<std::int64_t>{6, 5, 4}));
}

TEST_F(H5mdLayout, UnitsNameMdAnalysisBaseUnitsOrTheReducedOnes) {
  const std::string all = "/particles/all/";
  {
    const H5File f(write(metadata()));
    EXPECT_EQ(f.text_attribute(all + "position/value", "unit"), "Angstrom");
    EXPECT_EQ(f.text_attribute(all + "velocity/value", "unit"), "Angstrom ps-1");
    EXPECT_EQ(f.text_attribute(all + "position/time", "unit"), "ps");
    EXPECT_EQ(f.text_attribute("/observables/kinetic_energy/value", "unit"), "kJ mol-1");
    EXPECT_TRUE(f.exists("/h5md/modules/units"));
  }
  fs::remove(dir_ / "run.h5");
  RunMetadata reduced = metadata();
  reduced.unit_labels = UnitLabels::kReduced;
  const H5File f(write(reduced));
  EXPECT_EQ(f.text_attribute(all + "position/value", "unit"), "d");
  EXPECT_EQ(f.text_attribute(all + "velocity/value", "unit"), "u0");
  EXPECT_EQ(f.text_attribute(all + "position/time", "unit"), "d u0-1");
  EXPECT_EQ(f.text_attribute("/observables/kinetic_energy/value", "unit"), "m u0+2");
}

TEST_F(H5mdLayout, DtIsTheFrameIntervalAndAPeriodicBoxHasEdges) {
  {
    const H5File f(write(metadata()));
    EXPECT_EQ(f.values<double>("/observables/dt/value"), (std::vector<double>{0.5, 0.5, 0.5}));
    EXPECT_EQ(f.fixed_strings("/particles/all/box", "boundary"),
              (std::vector<std::string>{"none", "none", "none"}));
    EXPECT_FALSE(f.exists("/particles/all/box/edges"));
  }
  fs::remove(dir_ / "run.h5");
  RunMetadata periodic = metadata();
  periodic.periodic_box = {4.0, 5.0, 6.0};
  const H5File f(write(periodic));
  EXPECT_EQ(f.fixed_strings("/particles/all/box", "boundary"),
            (std::vector<std::string>{"periodic", "periodic", "periodic"}));
  ASSERT_EQ(f.shape("/particles/all/box/edges/value"), (std::vector<hsize_t>{3, 3, 3}));
  const auto edges = f.values<double>("/particles/all/box/edges/value");
  EXPECT_EQ(std::vector<double>(edges.begin() + 18, edges.end()),
            (std::vector<double>{4, 0, 0, 0, 5, 0, 0, 0, 6}));
  EXPECT_EQ(f.text_attribute("/particles/all/box/edges/value", "unit"), "Angstrom");
}

TEST_F(H5mdLayout, OmegaForceAndContactsAreStoredOnlyWhenAskedFor) {
  {
    const H5File f(write(metadata()));
    for (const char* absent :
         {"/particles/all/omega", "/particles/all/force", "/connectivity", "/contacts"})
      EXPECT_FALSE(f.exists(absent)) << absent;
  }
  fs::remove(dir_ / "run.h5");
  RunMetadata meta = metadata();
  meta.omega = meta.force = meta.contacts = true;
  const H5File f(write(meta));
  const auto omega = f.values<double>("/particles/all/omega/value");
  const auto force = f.values<double>("/particles/all/force/value");
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(omega[(kRows + 4) * 3 + a], Vec<3>(0.4, 0.0, 1.0)[a]);  // frame 1, grain 4
    EXPECT_EQ(force[(kRows + 4) * 3 + a], Vec<3>(4.0, 1.0, 2.0)[a]);
    EXPECT_TRUE(std::isnan(force[(kRows + 2) * 3 + a]));  // grain 2 left after frame 0
  }
  // Two pairs at most (frame 1): the plate's contacts are left out, unused rows hold -1.
  ASSERT_EQ(f.shape("/connectivity/contacts/value"), (std::vector<hsize_t>{3, 2, 2}));
  EXPECT_EQ(f.values<std::int64_t>("/connectivity/contacts/value"),
            (std::vector<std::int64_t>{5, 0, -1, -1, 0, 1, 1, 3, -1, -1, -1, -1}));
  EXPECT_EQ(f.values<std::int64_t>("/observables/frame_contacts/value"),
            (std::vector<std::int64_t>{1, 2, 0}));
  const auto normal = f.values<double>("/contacts/normal_force/value");
  EXPECT_EQ(normal[(2 + 1) * 3 + 2], 2.0);  // frame 1, contact 1: (0, 0, 2)
  const auto overlap = f.values<double>("/contacts/overlap/value");
  EXPECT_EQ(overlap[0], 0.01);
  EXPECT_TRUE(std::isnan(overlap[1]));
  EXPECT_EQ(f.values<std::int64_t>("/connectivity/contacts/step"),
            (std::vector<std::int64_t>{0, 10, 20}));
}

}  // namespace
}  // namespace granjet::analysis
