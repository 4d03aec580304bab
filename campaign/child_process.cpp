#include "campaign/child_process.hpp"

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

extern char** environ;

namespace granjet {

ChildProcess::ChildProcess(const std::vector<std::string>& args, const std::filesystem::path& log)
    : start_(std::chrono::steady_clock::now()) {
  // The running binary itself, even if a rebuild has replaced the file since it started: every
  // run of a campaign is made by the same code.
  const char* self = "/proc/self/exe";
  const std::string program = std::filesystem::read_symlink(self).string();
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  const int error = posix_spawn(&pid_, self, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw std::runtime_error("cannot start " + program + " (log " + log.string() +
                             "): " + std::strerror(error));
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)),
      code_(other.code_),
      start_(other.start_),
      end_(other.end_) {}

ChildProcess::~ChildProcess() {
  if (pid_ > 0 && !code_) wait();
}

std::optional<int> ChildProcess::reap(int options) {
  if (code_ || pid_ <= 0) return code_;
  int status = 0;
  pid_t r;
  do r = waitpid(pid_, &status, options);
  while (r < 0 && errno == EINTR);
  if (r == 0) return std::nullopt;
  end_ = std::chrono::steady_clock::now();
  if (r < 0)
    code_ = 1;  // lost track of the child: report a failure rather than wait forever
  else
    code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return code_;
}

std::optional<int> ChildProcess::poll() { return reap(WNOHANG); }

int ChildProcess::wait() { return *reap(0); }

double ChildProcess::seconds() const {
  const auto end = code_ ? end_ : std::chrono::steady_clock::now();
  return std::chrono::duration<double>(end - start_).count();
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

}  // namespace granjet
