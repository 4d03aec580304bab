// Ownership of HDF5 identifiers and the conversion of failed HDF5 calls into exceptions.
// Private to granjet_analysis: only its .cpp files see <hdf5.h>.
#pragma once

#include <hdf5.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

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

// Turns failed HDF5 calls on one file into std::runtime_error naming the file and the object.
// HDF5's own error stack is silenced: it prints library internals that do not help a user.
class H5Context {
 public:
  explicit H5Context(std::filesystem::path file) : file_(std::move(file)) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }

  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(std::string_view action, std::string_view object) const {
    throw std::runtime_error("'" + file_.string() + "': cannot " + std::string(action) + " " +
                             std::string(object));
  }
  H5Handle own(hid_t id, H5Handle::Closer close, std::string_view action,
               std::string_view object) const {
    if (id < 0) fail(action, object);
    return {id, close};
  }
  void check(herr_t status, std::string_view action, std::string_view object) const {
    if (status < 0) fail(action, object);
  }

 private:
  std::filesystem::path file_;
};

}  // namespace granjet::analysis
