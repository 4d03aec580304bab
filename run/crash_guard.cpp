#include "run/crash_guard.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <string>

#include "analysis/file_lock.hpp"
#include "core/errors.hpp"
#include "run/failure_report.hpp"

namespace granjet {
namespace {

bool is_crash(int signal) {
  return signal == SIGSEGV || signal == SIGBUS || signal == SIGABRT || signal == SIGFPE ||
         signal == SIGILL;
}

// Removes `scratch` unless another process holds it (then it is that one's, not the child's).
void remove_unless_held(const std::filesystem::path& scratch) {
  try {
    const analysis::FileLock lock(scratch);
    std::filesystem::remove(scratch);
  } catch (const analysis::FileBusyError&) {
  }
}

}  // namespace

int run_guarded(const std::function<int()>& command, const std::filesystem::path& file,
                const std::filesystem::path& scratch) {
  std::cout.flush();  // nothing buffered may be printed twice
  std::cerr.flush();
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  if (child == 0) {
    int code = 1;
    try {
      code = command();
    } catch (...) {
      code = report_current_exception(std::cerr);
    }
    std::cout.flush();
    std::cerr.flush();
    _exit(code);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error(std::string("cannot wait: ") + std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  const int signal = WTERMSIG(status);
  if (!scratch.empty()) remove_unless_held(scratch);
  if (!is_crash(signal)) {  // a kill from outside: passed on, as the shell expects
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
  throw InputError(file.string(), std::string("HDF5 crashed reading it (") + strsignal(signal) +
                                      "): the file is damaged; it was left as it was");
}

}  // namespace granjet
