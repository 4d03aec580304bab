// Ownership of HDF5 identifiers and the conversion of failed HDF5 calls into exceptions.
// Private to granjet_analysis: only its .cpp files see <hdf5.h>.
#pragma once

#include <hdf5.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace granjet::analysis {

// Owns one HDF5 identifier of any kind; `close` (H5Fclose, H5Dclose, ...) says which, so one
// class covers files, groups, datasets, attributes, dataspaces, types and property lists.
class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  H5Handle() = default;
  H5Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  H5Handle(H5Handle&& other) noexcept
      : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}
  H5Handle& operator=(H5Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      close_ = other.close_;
    }
    return *this;
  }
  ~H5Handle() { reset(); }

  hid_t get() const { return id_; }
  // Returns the close status: closing a file writes its last metadata, which can fail.
  herr_t reset() {
    const herr_t status = id_ >= 0 ? close_(id_) : 0;
    id_ = H5I_INVALID_HID;
    return status;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer close_ = nullptr;
};

// Turns failed HDF5 calls on one file into exceptions naming the file and the object: an
// InputError (exit code 2) for a file granjet reads, a std::runtime_error for one it writes.
// HDF5's own error stack is silenced: it prints library internals that do not help a user.
class H5Context {
 public:
  enum class Role { kOutput, kInput };

  explicit H5Context(std::filesystem::path file, Role role = Role::kOutput)
      : file_(std::move(file)), role_(role) {
    // Before the library's first call: no clean-up at exit. A file whose last write failed
    // (a full disk) cannot be closed, and HDF5's own clean-up would crash on it at exit.
    static const bool kNoCleanUpAtExit = [] { return H5dont_atexit() >= 0; }();
    (void)kNoCleanUpAtExit;
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }

  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(std::string_view action, std::string_view object) const {
    std::string what = "cannot ";
    what.append(action).append(" ").append(object);
    const std::string reason = system_reason();
    if (!reason.empty()) what.append(": ").append(reason);
    if (role_ == Role::kInput) throw InputError(file_.string(), what);
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "'" + std::string once inlined.
    std::string message = "'";
    message.append(file_.string()).append("': ").append(what);
    if (reason == std::strerror(ENOSPC) || reason == std::strerror(EDQUOT))
      throw DiskFullError(message);
    throw std::runtime_error(message);
  }
  H5Handle own(hid_t id, H5Handle::Closer close, std::string_view action,
               std::string_view object) const {
    if (id < 0) fail(action, object);
    return {id, close};
  }
  void check(herr_t status, std::string_view action, std::string_view object) const {
    if (status < 0) fail(action, object);
  }

  // A dataspace of shape `dims`, scalar when `dims` is empty.
  H5Handle dataspace(const std::vector<hsize_t>& dims) const {
    const hid_t space = dims.empty()
                            ? H5Screate(H5S_SCALAR)
                            : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    return own(space, H5Sclose, "create", "a dataspace");
  }
  // A C string type of `size` bytes, the trailing NUL counted (H5T_VARIABLE: variable length).
  H5Handle string_type(std::size_t size) const {
    H5Handle type = own(H5Tcopy(H5T_C_S1), H5Tclose, "create", "a string type");
    check(H5Tset_size(type.get(), size), "size", "a string type");
    return type;
  }
  // Attribute `name` of `object` in the open `file`. An attribute cannot change its size, so a
  // new value replaces an existing one.
  void write_attribute(hid_t file, const std::string& object, const char* name, hid_t type,
                       hid_t space, const void* data) const {
    const std::string what = object + " attribute " + name;
    if (H5Aexists_by_name(file, object.c_str(), name, H5P_DEFAULT) > 0)
      check(H5Adelete_by_name(file, object.c_str(), name, H5P_DEFAULT), "replace", what);
    const H5Handle attribute = own(H5Acreate_by_name(file, object.c_str(), name, type, space,
                                                     H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                   H5Aclose, "create", what);
    check(H5Awrite(attribute.get(), type, data), "write", what);
  }
  void write_string_attribute(hid_t file, const std::string& object, const char* name,
                              const std::string& value) const {
    write_attribute(file, object, name, string_type(value.size() + 1).get(), dataspace({}).get(),
                    value.c_str());
  }

  // The operating system's reason for the failure HDF5 just reported, where its error stack
  // holds one (its file drivers record errno's text: "No space left on device"); else empty.
  static std::string system_reason() {
    std::string reason;
    const auto find = [](unsigned, const H5E_error2_t* error, void* out) -> herr_t {
      std::string& text = *static_cast<std::string*>(out);
      if (!text.empty() || error->desc == nullptr) return 0;
      const std::string_view desc(error->desc), key("error message = '");
      const std::size_t start = desc.find(key);
      if (start == std::string_view::npos) return 0;
      const std::size_t end = desc.find('\'', start + key.size());
      text =
          desc.substr(start + key.size(), end == std::string_view::npos ? std::string_view::npos
                                                                        : end - start - key.size());
      return 0;
    };
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, find, &reason);
    return reason;
  }

  // The file, read-only and without HDF5's file lock, so that a user can look into a run's
  // .partial while it is written (the writer flushes every frame).
  H5Handle open_read_only() const {
    const H5Handle access =
        own(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create", "file access properties");
    check(H5Pset_file_locking(access.get(), false, true), "set", "file locking");
    return own(H5Fopen(file_.c_str(), H5F_ACC_RDONLY, access.get()), H5Fclose, "open",
               "the HDF5 file");
  }

 private:
  std::filesystem::path file_;
  Role role_;
};

}  // namespace granjet::analysis
