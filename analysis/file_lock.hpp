// An exclusive lock on a file being written, held for as long as the writer lives: a second run
// with the same --out finds it busy instead of truncating the first one's file. Linux
// open-file-description locks: they go with the process when it dies (kill -9 included), and
// they do not meet HDF5's own flock() locks.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <utility>

namespace granjet::analysis {

// Another process holds the lock.
class FileBusyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FileLock {
 public:
  // Creates `path` if missing (empty; never truncates) and locks it. Throws FileBusyError when
  // another process holds it, std::runtime_error when it cannot be opened.
  explicit FileLock(const std::filesystem::path& path);
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  // The lock goes with the open file, so it survives a rename of the file it is on.
  FileLock(FileLock&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  ~FileLock();

  // Whether another process holds the lock on `path`, without creating or locking it (false
  // when it does not exist).
  static bool held(const std::filesystem::path& path);

 private:
  int fd_ = -1;
};

}  // namespace granjet::analysis
