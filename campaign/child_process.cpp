#include "campaign/child_process.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "campaign/mpi_world.hpp"

extern char** environ;

namespace granjet {
namespace {

// Names the parent a child is to end with (its process id).
constexpr const char* kParentVariable = "GRANJET_END_WITH_PARENT";

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& args, const std::filesystem::path& log)
    : start_(std::chrono::steady_clock::now()) {
  // The running binary itself, even if a rebuild has replaced the file since it started: every
  // run of a campaign is made by the same code.
  const char* self = "/proc/self/exe";
  const std::string program = std::filesystem::read_symlink(self).string();
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  // The environment, with this process named as the parent to end with, and without the world
  // size of an mpirun that started this one: each run is a process of its own, not one of the
  // launcher's ranks (launched_ranks, core/rank_team.hpp), and one run refuses several ranks.
  const std::string parent = std::string(kParentVariable) + "=" + std::to_string(getpid());
  std::vector<char*> env{const_cast<char*>(parent.c_str())};
  const auto kept = [](std::string_view entry) {
    if (entry.starts_with(kParentVariable)) return false;
    for (std::string_view name : kLaunchedRanksVariables)
      if (entry.starts_with(name) && entry.substr(name.size()).starts_with('=')) return false;
    return true;
  };
  for (char** e = environ; *e != nullptr; ++e)
    if (kept(*e)) env.push_back(*e);
  env.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);  // a group of its own
  const int error = posix_spawn(&pid_, self, &actions, &attributes, argv.data(), env.data());
  posix_spawnattr_destroy(&attributes);
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

void ChildProcess::signal(int signal) {
  if (pid_ > 0 && !code_) ::kill(pid_, signal);
}

void end_with_parent() {
  const char* parent = std::getenv(kParentVariable);
  if (parent == nullptr) return;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The parent may have died before the line above: then the child is an orphan already.
  if (std::to_string(getppid()) != parent) _exit(128 + SIGKILL);
}

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return std::max(1, CPU_COUNT(&set));
}

}  // namespace granjet
