// copy_hdf5_except: what a re-analysis keeps of a file. Everything
// but the left-out groups, with attributes of every kind (object references made again in the
// copy), hard links (in a group and across groups) still one object, soft links still soft; the
// left-out groups never opened.
#include "analysis/hdf5_copy.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "../common/hdf5_text.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

void string_attribute(hid_t object, const char* name, const char* value, bool variable) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, variable ? H5T_VARIABLE : std::string(value).size() + 1);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(object, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (variable)
    H5Awrite(a, type, &value);
  else
    H5Awrite(a, type, value);
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
}

std::string read_string(hid_t file, const char* object, const char* name) {
  return testing::string_attribute(file, object, name);
}

void dataset(hid_t file, const char* name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t set =
      H5Dcreate2(file, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  string_attribute(set, "unit", "d u0-1", true);
  H5Dclose(set);
  H5Sclose(space);
}

std::vector<double> read_dataset(hid_t file, const char* name) {
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
  H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(set);
  return values;
}

// An attribute particles_group of `object` that refers to /particles, as in H5MD's connectivity.
void refer_to_particles(hid_t file, const char* object) {
  hobj_ref_t ref;
  H5Rcreate(&ref, file, "/particles", H5R_OBJECT, -1);
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate_by_name(file, object, "particles_group", H5T_STD_REF_OBJ, scalar,
                                    H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_STD_REF_OBJ, &ref);
  H5Aclose(a);
  H5Sclose(scalar);
}

// The path of the object that the reference in `object`'s attribute `attribute` points to.
std::string referenced_path(hid_t file, const char* object, const char* attribute) {
  hobj_ref_t ref;
  const hid_t a = H5Aopen_by_name(file, object, attribute, H5P_DEFAULT, H5P_DEFAULT);
  H5Aread(a, H5T_STD_REF_OBJ, &ref);
  H5Aclose(a);
  const hid_t target = H5Rdereference2(file, H5P_DEFAULT, H5R_OBJECT, &ref);
  if (target < 0) return "(none)";
  char name[64] = {};
  H5Iget_name(target, name, sizeof name);
  H5Oclose(target);
  return name;
}

haddr_t address(hid_t file, const char* name) {
  H5O_info_t info;
  H5Oget_info_by_name(file, name, &info, H5P_DEFAULT);
  return info.addr;
}

// /h5md (attributes), /observables/{a,b} (b/time a hard link to a/time), /particles/step (a
// hard link across groups), /particles/soft -> /observables/a, and /fields, /analysis: an
// external link to a file that is not there, which fails whoever follows it.
void write_source(const fs::path& file) {
  const hid_t f = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t h5md = H5Gcreate2(f, "/h5md", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  string_attribute(h5md, "creator", "granjet", false);
  string_attribute(h5md, "note", "variable length", true);
  const int version[2] = {1, 1};
  const hsize_t two = 2;
  const hid_t pair = H5Screate_simple(1, &two, nullptr);
  const hid_t v = H5Acreate2(h5md, "version", H5T_NATIVE_INT, pair, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(v, H5T_NATIVE_INT, version);
  H5Aclose(v);
  H5Sclose(pair);
  H5Gclose(h5md);
  for (const char* group : {"/observables", "/observables/a", "/observables/b", "/particles"})
    H5Gclose(H5Gcreate2(f, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  dataset(f, "/observables/a/time", {0.0, 0.5, 1.0});
  dataset(f, "/observables/a/value", {3.0, 2.0, 1.0});
  H5Lcreate_hard(f, "/observables/a/time", f, "/observables/b/time", H5P_DEFAULT, H5P_DEFAULT);
  H5Lcreate_hard(f, "/observables/a/time", f, "/particles/step", H5P_DEFAULT, H5P_DEFAULT);
  H5Lcreate_soft("/observables/a", f, "/particles/soft", H5P_DEFAULT, H5P_DEFAULT);
  // An object reference, as H5MD's connectivity names its particles group: on a group copied
  // before the object it points to.
  refer_to_particles(f, "/observables/a");
  for (const char* left_out : {"/fields", "/analysis"})
    H5Lcreate_external("missing.h5", "/", f, left_out, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(f);
}

TEST(Hdf5Copy, KeepsAttributesAndLinksAndNeverOpensTheLeftOutGroups) {
  const fs::path dir = fs::temp_directory_path() / "granjet_hdf5_copy";
  fs::remove_all(dir);
  fs::create_directories(dir);
  write_source(dir / "run.h5");
  copy_hdf5_except(dir / "run.h5", dir / "copy.h5", {"fields", "analysis"});

  const hid_t f = H5Fopen((dir / "copy.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(H5Lexists(f, "/fields", H5P_DEFAULT), 0);
  EXPECT_EQ(H5Lexists(f, "/analysis", H5P_DEFAULT), 0);
  EXPECT_EQ(read_string(f, "/h5md", "creator"), "granjet");
  EXPECT_EQ(read_string(f, "/h5md", "note"), "variable length");
  EXPECT_EQ(read_string(f, "/observables/a/value", "unit"), "d u0-1");
  int version[2] = {0, 0};
  const hid_t v = H5Aopen_by_name(f, "/h5md", "version", H5P_DEFAULT, H5P_DEFAULT);
  H5Aread(v, H5T_NATIVE_INT, version);
  H5Aclose(v);
  EXPECT_EQ(version[0], 1);
  EXPECT_EQ(version[1], 1);
  EXPECT_EQ(read_dataset(f, "/observables/a/value"), (std::vector<double>{3.0, 2.0, 1.0}));
  EXPECT_EQ(read_dataset(f, "/particles/step"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(address(f, "/observables/b/time"), address(f, "/observables/a/time"));
  EXPECT_EQ(address(f, "/particles/step"), address(f, "/observables/a/time"));
  H5L_info_t soft;
  ASSERT_GE(H5Lget_info(f, "/particles/soft", &soft, H5P_DEFAULT), 0);
  EXPECT_EQ(soft.type, H5L_TYPE_SOFT);
  EXPECT_EQ(address(f, "/particles/soft"), address(f, "/observables/a"));
  // The reference points to the copy's /particles, not to an address of the source.
  EXPECT_EQ(referenced_path(f, "/observables/a", "particles_group"), "/particles");
  H5Fclose(f);

  // Followed, an external link fails, and a copy that keeps it names it and the source.
  try {
    copy_hdf5_except(dir / "run.h5", dir / "copy.h5", {"fields"});
    ADD_FAILURE() << "an external link was copied";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/analysis"), std::string::npos) << e.what();
  }
  EXPECT_THROW(copy_hdf5_except(dir / "none.h5", dir / "copy.h5", {}), InputError);
  fs::remove_all(dir);
}

// A group that a kill left half-written, its object header garbled, as a run killed while it
// stored its fields leaves it: the copy leaves it out and never reads it, also when it makes
// again an object reference elsewhere in the file (finding the referenced object's path by a
// search of the whole file would read the garbled header on the way).
TEST(Hdf5Copy, MakesReferencesAgainPastAGarbledGroupItLeavesOut) {
  const fs::path dir = fs::temp_directory_path() / "granjet_hdf5_copy_garbled";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path source = dir / "run.h5";
  {
    const hid_t f = H5Fcreate(source.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    for (const char* group : {"/connectivity", "/fields", "/particles"})
      H5Gclose(H5Gcreate2(f, group, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    dataset(f, "/fields/n", {1.0, 2.0});
    dataset(f, "/particles/x", {0.5});
    refer_to_particles(f, "/connectivity");
    H5Fclose(f);
  }
  const hid_t before = H5Fopen(source.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const haddr_t fields = address(before, "/fields");
  H5Fclose(before);
  {
    std::fstream garble(source, std::ios::in | std::ios::out | std::ios::binary);
    garble.seekp(static_cast<std::streamoff>(fields));
    const std::string junk(64, '\xff');
    garble.write(junk.data(), static_cast<std::streamsize>(junk.size()));
  }
  copy_hdf5_except(source, dir / "copy.h5", {"fields"});

  const hid_t f = H5Fopen((dir / "copy.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(H5Lexists(f, "/fields", H5P_DEFAULT), 0);
  EXPECT_EQ(read_dataset(f, "/particles/x"), (std::vector<double>{0.5}));
  EXPECT_EQ(referenced_path(f, "/connectivity", "particles_group"), "/particles");
  H5Fclose(f);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granjet::analysis
