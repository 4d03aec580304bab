// A child process started from the granjet binary itself, its output going to a log file: the
// way a campaign runs each run in a process of its own (HDF5 as packaged is not thread-safe, and
// a run that crashes takes only itself down).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace granjet {

class ChildProcess {
 public:
  // Starts this very binary (/proc/self/exe) with `args`, stdin from /dev/null and stdout and
  // stderr appended to `log`. Throws std::runtime_error naming the log or the program on failure.
  ChildProcess(const std::vector<std::string>& args, const std::filesystem::path& log);
  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&&) = delete;
  ChildProcess(const ChildProcess&) = delete;
  ~ChildProcess();  // a child still running is waited for

  // The exit code once the child has ended (128 + the signal if a signal ended it), without
  // waiting; std::nullopt while it runs.
  std::optional<int> poll();
  // Waits for the end and returns the exit code as poll() does.
  int wait();
  // Wall time from the start to the end (or to now while it runs).
  double seconds() const;

 private:
  std::optional<int> reap(int options);

  pid_t pid_ = -1;
  std::optional<int> code_;
  std::chrono::steady_clock::time_point start_, end_;
};

// The cores this process may run on (its CPU affinity).
int available_cores();

}  // namespace granjet
