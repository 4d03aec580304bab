// Runs the granjet command in a fresh temporary directory per test and keeps its stderr.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace granjet::testing {

class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The process id too: two test runs at once (two build trees) must not share directories.
    dir_ = std::filesystem::temp_directory_path() /
           ("granjet_cmd_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_suite()->name()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" +
            std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Runs granjet with `args`; returns the exit code, stderr into err_.
  int granjet(const std::string& args) {
    const std::filesystem::path err = dir_ / "stderr.txt";
    const std::string cmd = std::string(GRANJET_BINARY) + " " + args + " > " +
                            (dir_ / "stdout.txt").string() + " 2> " + err.string();
    return run_reading(cmd, err);
  }
  // Runs the shell command `cmd`; returns its exit code, the text of `said` (where it wrote)
  // into err_.
  int run_reading(const std::string& cmd, const std::filesystem::path& said) {
    const int status = std::system(cmd.c_str());
    std::ifstream in(said);
    std::stringstream s;
    s << in.rdbuf();
    err_ = s.str();
    return WEXITSTATUS(status);
  }
#ifdef GRANJET_MPIEXEC
  // The start of a command line that runs over `ranks` MPI ranks: root needs
  // --allow-run-as-root, several ranks on a machine of any size need --oversubscribe.
  static std::string mpiexec(int ranks) {
    return std::string(GRANJET_MPIEXEC) + " --allow-run-as-root --oversubscribe -n " +
           std::to_string(ranks) + " ";
  }
  // Runs granjet with `args` over `ranks` ranks, ended after 5 minutes should it hang;
  // returns mpiexec's exit code, its stdout and stderr into err_.
  int granjet_over_ranks(int ranks, const std::string& args) {
    const std::filesystem::path said = dir_ / "mpiexec.txt";
    const std::string cmd = "timeout 300 " + mpiexec(ranks) + GRANJET_BINARY + " " + args + " > " +
                            said.string() + " 2>&1";
    return run_reading(cmd, said);
  }
#endif
  // A file's bytes: to see that a refused command left it as it was.
  static std::string bytes_of(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  static std::string scene(const std::string& name) {
    return std::string(GRANJET_SCENES_DIR) + "/" + name;
  }
  // Whether h5diff finds the two files, or one object of each, the same.
  static bool same_hdf5(const std::filesystem::path& a, const std::filesystem::path& b,
                        const std::string& object = "") {
    std::string cmd = std::string(GRANJET_H5DIFF) + " -q " + a.string() + " " + b.string();
    if (!object.empty()) cmd += " " + object + " " + object;
    return std::system(cmd.c_str()) == 0;
  }
  // What h5diff says of two files, its first lines: for a failure's message.
  static std::string hdf5_differences(const std::filesystem::path& a,
                                      const std::filesystem::path& b) {
    const std::string cmd =
        std::string(GRANJET_H5DIFF) + " " + a.string() + " " + b.string() + " 2>&1 | head -n 20";
    std::string said;
    if (FILE* pipe = popen(cmd.c_str(), "r")) {
      char line[512];
      while (std::fgets(line, sizeof line, pipe) != nullptr) said += line;
      pclose(pipe);
    }
    return said;
  }
  nlohmann::json summary(const std::string& name) const {
    std::ifstream in(dir_ / name);
    return nlohmann::json::parse(in);
  }

  std::filesystem::path dir_;
  std::string err_;
};

}  // namespace granjet::testing
