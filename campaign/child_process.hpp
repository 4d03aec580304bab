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
  // stderr appended to `log`, in a process group of its own: a Ctrl-C at the terminal reaches
  // the parent alone, which passes it on once (a second signal would stop the child at once).
  // The child dies with the parent (end_with_parent). Throws std::runtime_error naming the log
  // or the program on failure.
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
  // Sends `signal` to the child while it runs.
  void signal(int signal);

 private:
  std::optional<int> reap(int options);

  pid_t pid_ = -1;
  std::optional<int> code_;
  std::chrono::steady_clock::time_point start_, end_;
};

// The cores this process may run on (its CPU affinity).
int available_cores();

// Called first thing by the granjet command: a process started as a ChildProcess is killed
// when its parent dies (kill -9 of a campaign, a node that vanishes), as it would be in the
// parent's process group.
void end_with_parent();

}  // namespace granjet
