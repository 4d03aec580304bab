#include "analysis/hdf5_copy.hpp"

#include <hdf5.h>

#include <algorithm>
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
    // A dataset (or named type) with its attributes, in one call; references among them are
    // made again at the end.
    in_.check(H5Ocopy(from_, path.c_str(), to_, path.c_str(), H5P_DEFAULT, H5P_DEFAULT), "copy",
              path);
    const H5Handle copied =
        in_.own(H5Oopen(from_, path.c_str(), H5P_DEFAULT), H5Oclose, "open", path);
    note_references(copied.get(), path);
  }

  // An object reference points to an address in its file: each is made again in the copy, to
  // the object of the same path, once every object is there (H5MD's connectivity names its
  // particles group by one).
  void make_references() {
    for (const Reference& r : references_) {
      const std::string what = r.object + " attribute " + r.name;
      std::vector<hobj_ref_t> refs(r.targets.size());
      for (std::size_t k = 0; k < refs.size(); ++k) {
        const auto target = copied_.find(r.targets[k]);
        if (target == copied_.end()) in_.fail("follow (it leads to an object left out)", what);
        out_.check(H5Rcreate(&refs[k], to_, target->second.c_str(), H5R_OBJECT, -1), "refer to",
                   target->second);
      }
      if (H5Aexists_by_name(to_, r.object.c_str(), r.name.c_str(), H5P_DEFAULT) > 0)
        out_.check(H5Adelete_by_name(to_, r.object.c_str(), r.name.c_str(), H5P_DEFAULT), "replace",
                   what);
      const H5Handle space = out_.dataspace(r.shape);
      const H5Handle a =
          out_.own(H5Acreate_by_name(to_, r.object.c_str(), r.name.c_str(), H5T_STD_REF_OBJ,
                                     space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose, "create", what);
      out_.check(H5Awrite(a.get(), H5T_STD_REF_OBJ, refs.data()), "write", what);
    }
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

  // One attribute of an object in the source, open with its type and shape.
  struct Attribute {
    std::string name;
    H5Handle handle, type, space;
    std::size_t count = 0;
  };
  template <class Visit>
  void each_attribute(hid_t object, const std::string& path, const Visit& visit) const {
    H5O_info_t info;
    in_.check(H5Oget_info(object, &info), "read", path);
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
      const std::string what = path + " attribute " + std::to_string(k);
      Attribute a;
      a.handle = in_.own(
          H5Aopen_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose, "open", what);
      a.type = in_.own(H5Aget_type(a.handle.get()), H5Tclose, "read the type of", what);
      a.space = in_.own(H5Aget_space(a.handle.get()), H5Sclose, "read the shape of", what);
      const hssize_t count = H5Sget_simple_extent_npoints(a.space.get());
      const ssize_t length = H5Aget_name(a.handle.get(), 0, nullptr);
      if (count < 0 || length < 0 || H5Tget_size(a.type.get()) == 0) in_.fail("read", what);
      a.count = static_cast<std::size_t>(count);
      std::vector<char> name(static_cast<std::size_t>(length) + 1);
      H5Aget_name(a.handle.get(), name.size(), name.data());
      a.name = name.data();
      visit(a);
    }
  }

  // H5Ocopy copies a dataset's attributes along; a group made afresh gets them here.
  void attributes(hid_t source, hid_t copy, const std::string& path) {
    note_references(source, path);
    each_attribute(source, path, [&](const Attribute& a) {
      if (H5Tget_class(a.type.get()) == H5T_REFERENCE) return;
      const std::string what = path + " attribute " + a.name;
      std::vector<std::byte> value(a.count * H5Tget_size(a.type.get()));
      in_.check(H5Aread(a.handle.get(), a.type.get(), value.data()), "read", what);
      // Variable-length values are copied as the library's own allocations, freed after.
      const bool variable =
          H5Tdetect_class(a.type.get(), H5T_VLEN) > 0 || H5Tis_variable_str(a.type.get()) > 0;
      const H5Handle b = out_.own(
          H5Acreate2(copy, a.name.c_str(), a.type.get(), a.space.get(), H5P_DEFAULT, H5P_DEFAULT),
          H5Aclose, "create", what);
      const herr_t written = H5Awrite(b.get(), a.type.get(), value.data());
      if (variable) H5Dvlen_reclaim(a.type.get(), a.space.get(), H5P_DEFAULT, value.data());
      out_.check(written, "write", what);
    });
  }

  struct Reference {
    std::string object, name;
    std::vector<hsize_t> shape;
    std::vector<haddr_t> targets;  // addresses in the source, of objects copied (copied_)
  };

  // The object references among the attributes of `object`, by the addresses they point to.
  // Each is opened by its address: finding its path instead (H5Rget_name) searches the whole
  // file, and fails on a group a kill left half-written, which the copy may be there to leave
  // out (H5mdFile::drop_fields_and_analysis).
  void note_references(hid_t object, const std::string& path) {
    each_attribute(object, path, [&](const Attribute& a) {
      if (H5Tget_class(a.type.get()) != H5T_REFERENCE) return;
      const std::string what = path + " attribute " + a.name;
      if (H5Tequal(a.type.get(), H5T_STD_REF_OBJ) <= 0) in_.fail("copy the region reference", what);
      std::vector<hobj_ref_t> refs(a.count);
      in_.check(H5Aread(a.handle.get(), H5T_STD_REF_OBJ, refs.data()), "read", what);
      Reference r{path, a.name, {}, {}};
      const int rank = H5Sget_simple_extent_ndims(a.space.get());
      r.shape.resize(static_cast<std::size_t>(std::max(rank, 0)));
      if (rank > 0) H5Sget_simple_extent_dims(a.space.get(), r.shape.data(), nullptr);
      for (hobj_ref_t& ref : refs) {
        const H5Handle target = in_.own(H5Rdereference2(from_, H5P_DEFAULT, H5R_OBJECT, &ref),
                                        H5Oclose, "follow", what);
        H5O_info_t info;
        in_.check(H5Oget_info(target.get(), &info), "follow", what);
        r.targets.push_back(info.addr);
      }
      references_.push_back(std::move(r));
    });
  }

  const H5Context& in_;
  const H5Context& out_;
  hid_t from_;
  hid_t to_;
  std::map<haddr_t, std::string> copied_;  // object address in `source` -> its first path
  std::vector<Reference> references_;
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
  copier.make_references();
  out.check(to.reset(), "close", "the file");
}

}  // namespace granjet::analysis
