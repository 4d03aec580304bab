#include "analysis/hdf5_copy.hpp"

#include <hdf5.h>

#include <cstddef>
#include <map>
#include <vector>

#include "analysis/hdf5_handle.hpp"

namespace granjet::analysis {
namespace {

// Names of the links in `group`, in name order.
std::vector<std::string> link_names(const H5Context& in, hid_t group, const std::string& path) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* list) -> herr_t {
    static_cast<std::vector<std::string>*>(list)->emplace_back(name);
    return 0;
  };
  in.check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names), "list", path);
  return names;
}

class Copier {
 public:
  Copier(const H5Context& in, const H5Context& out, hid_t from, hid_t to)
      : in_(in), out_(out), from_(from), to_(to) {}

  // Copies the link `path` (absolute) and what it leads to.
  void link(const std::string& path) {
    H5L_info_t info;
    in_.check(H5Lget_info(from_, path.c_str(), &info, H5P_DEFAULT), "read the link", path);
    if (info.type == H5L_TYPE_SOFT) return soft_link(path, info.u.val_size);
    if (info.type != H5L_TYPE_HARD) in_.fail("copy the external link", path);
    const auto [first, fresh] = copied_.try_emplace(info.u.address, path);
    if (!fresh) {
      out_.check(
          H5Lcreate_hard(to_, first->second.c_str(), to_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          "link", path);
      return;
    }
    H5O_info_t object;
    in_.check(H5Oget_info_by_name(from_, path.c_str(), &object, H5P_DEFAULT), "read", path);
    if (object.type == H5O_TYPE_GROUP) return group(path);
    // A dataset (or named type) with its attributes, in one call.
    in_.check(H5Ocopy(from_, path.c_str(), to_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT), "copy",
              path);
  }

 private:
  void soft_link(const std::string& path, std::size_t size) {
    std::vector<char> value(size);
    in_.check(H5Lget_val(from_, path.c_str(), value.data(), size, H5P_DEFAULT), "read the link",
              path);
    out_.check(H5Lcreate_soft(value.data(), to_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT), "link",
               path);
  }

  void group(const std::string& path) {
    const H5Handle source =
        in_.own(H5Gopen2(from_, path.c_str(), H5P_DEFAULT), H5Gclose, "open", path);
    const H5Handle copy =
        out_.own(H5Gcreate2(to_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "create", path);
    attributes(source.get(), copy.get(), path);
    for (const std::string& name : link_names(in_, source.get(), path)) link(path + "/" + name);
  }

  // H5Ocopy copies a dataset's attributes along; a group made afresh gets them here.
  void attributes(hid_t source, hid_t copy, const std::string& path) {
    H5O_info_t object;
    in_.check(H5Oget_info(source, &object), "read", path);
    for (hsize_t k = 0; k < object.num_attrs; ++k) {
      const std::string what = path + " attribute " + std::to_string(k);
      const H5Handle a = in_.own(
          H5Aopen_by_idx(source, ".", H5_INDEX_NAME, H5_ITER_INC, k, H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose, "open", what);
      const H5Handle type = in_.own(H5Aget_type(a.get()), H5Tclose, "read the type of", what);
      const H5Handle space = in_.own(H5Aget_space(a.get()), H5Sclose, "read the shape of", what);
      const hssize_t count = H5Sget_simple_extent_npoints(space.get());
      const std::size_t size = H5Tget_size(type.get());
      if (count < 0 || size == 0) in_.fail("read", what);
      std::vector<std::byte> value(static_cast<std::size_t>(count) * size);
      in_.check(H5Aread(a.get(), type.get(), value.data()), "read", what);
      // Variable-length values are copied as the library's own allocations, freed after.
      const bool variable =
          H5Tdetect_class(type.get(), H5T_VLEN) > 0 || H5Tis_variable_str(type.get()) > 0;
      std::vector<char> name(static_cast<std::size_t>(H5Aget_name(a.get(), 0, nullptr)) + 1);
      H5Aget_name(a.get(), name.size(), name.data());
      const H5Handle b =
          out_.own(H5Acreate2(copy, name.data(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create", path + " attribute " + name.data());
      const herr_t written = H5Awrite(b.get(), type.get(), value.data());
      if (variable) H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, value.data());
      out_.check(written, "write", path + " attribute " + name.data());
    }
  }

  const H5Context& in_;
  const H5Context& out_;
  hid_t from_;
  hid_t to_;
  std::map<haddr_t, std::string> copied_;  // object address in `source` -> its first path
};

}  // namespace

void copy_hdf5_except(const std::filesystem::path& source, const std::filesystem::path& target,
                      const std::set<std::string>& left_out) {
  const H5Context in(source, H5Context::Role::kInput);
  const H5Context out(target);
  const H5Handle from = in.open_read_only();
  H5Handle to = out.own(H5Fcreate(target.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                        H5Fclose, "create", "the HDF5 file");
  Copier copier(in, out, from.get(), to.get());
  for (const std::string& name : link_names(in, from.get(), "/"))
    if (!left_out.contains(name)) copier.link("/" + name);
  out.check(to.reset(), "close", "the file");
}

}  // namespace granjet::analysis
