// run_guarded: a command in a child process. Its exit code and its exceptions' exit codes come
// back as they would without the child; a crash becomes an InputError naming the file, and the
// child's scratch file goes unless another process holds it.
#include "run/crash_guard.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "analysis/file_lock.hpp"
#include "core/errors.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

TEST(CrashGuard, ExitCodesAndExceptionsComeBackFromTheChild) {
  EXPECT_EQ(run_guarded([] { return 0; }, "run.h5"), 0);
  EXPECT_EQ(run_guarded([] { return 5; }, "run.h5"), 5);
  EXPECT_EQ(run_guarded([]() -> int { throw InputError("run.h5", "bad"); }, "run.h5"), 2);
  EXPECT_EQ(run_guarded([]() -> int { throw std::runtime_error("disk"); }, "run.h5"), 1);
}

TEST(CrashGuard, ACrashNamesTheFileAndRemovesTheScratch) {
  const fs::path dir = fs::temp_directory_path() / "granjet_crash_guard";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scratch = dir / "run.h5.reanalysis";
  const auto crash = [&] {
    std::ofstream(scratch) << "half written";
    std::raise(SIGSEGV);
    return 0;
  };
  try {
    run_guarded(crash, dir / "run.h5", scratch);
    ADD_FAILURE() << "the crash was not reported";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("run.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("damaged"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(scratch));

  // A scratch file another process is writing (here: this one, holding its lock) stays.
  std::ofstream(scratch) << "another analysis";
  {
    const analysis::FileLock held(scratch);
    EXPECT_THROW(run_guarded([] { return std::raise(SIGABRT); }, dir / "run.h5", scratch),
                 InputError);
  }
  EXPECT_TRUE(fs::exists(scratch));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granjet
