// `granjet resume`: a run killed with SIGKILL after a checkpoint and resumed gives
// the straight run's frames, observables, fields, analysis and summary (minus timings), bit for
// bit; a resume may extend run.t_end and nothing that would make it another run.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>
#include <utility>
#include <vector>

#include "analysis/checkpoint_file.hpp"
#include "analysis/h5md_reader.hpp"
#include "command_fixture.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

class Resume : public testing::CommandTest {
 protected:
  // Starts `LAUNCHER granjet ARGS` (stderr into the test's directory) and sends it `signals`
  // once its .partial holds a checkpoint at `after` or later. Returns its wait status, or -1 if
  // it ended first.
  int run_and_signal(const std::string& args, const fs::path& partial, double after,
                     const std::vector<int>& signals, const std::string& launcher = "") {
    const pid_t child = fork();
    if (child == 0) {
      const std::string cmd = launcher + GRANJET_BINARY + " " + args + " > /dev/null 2> " +
                              (dir_ / "stderr.txt").string();
      execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), nullptr);
      _exit(127);
    }
    bool sent = false;
    for (int k = 0; k < 6000 && !sent; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      int status = 0;
      if (waitpid(child, &status, WNOHANG) == child) return -1;  // ended on its own
      try {
        const analysis::FileSummary s = analysis::read_summary(partial);
        if (s.checkpoint && s.checkpoint_time >= after) {
          for (int signal : signals) kill(child, signal);
          if (!launcher.empty()) {  // the pattern matches no shell that runs pkill
            const fs::path run = partial.parent_path() / partial.stem().stem();
            std::system(("pkill -KILL -f '" + run.string() + "[.]h5'").c_str());
          }
          sent = true;
        }
      } catch (const std::exception&) {
        // not yet created, or caught mid-write: look again
      }
    }
    int status = 0;
    waitpid(child, &status, 0);
    std::ifstream in(dir_ / "stderr.txt");
    err_.assign(std::istreambuf_iterator<char>(in), {});
    return sent ? status : -1;
  }
  // SIGKILL: nothing of the run's own goes on.
  bool run_and_kill(const std::string& args, const fs::path& partial, double after) {
    const int status = run_and_signal(args, partial, after, {SIGKILL});
    return status != -1 && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  }

  // A jet3d run of 2,000 grains to `t_end` with every kind of output: frames every unit of time
  // with forces and contacts, a checkpoint every 2, inline analysis from t = 2.
  static std::string small_jet3d_run(const std::string& t_end) {
    return "run " + scene("jet3d.ini") +
           " --quiet --set jet.grains=2000 --set wall.diameter=14 --set run.t_end=" + t_end +
           " --set analysis.window_start=2 --set analysis.window_end=" + t_end +
           " --set run.checkpoint_interval=2 --set output.interval=1"
           " --set output.fields=position,velocity,radius,id,omega,force,contacts";
  }

  // The output and summary options of a run named `name` in the test's directory.
  std::string paths(const std::string& name) const {
    return " --out " + (dir_ / (name + ".h5")).string() + " --summary " +
           (dir_ / (name + ".json")).string();
  }

  static nlohmann::json without_timings(nlohmann::json j) {
    for (const char* key : {"wall_seconds", "cpu_seconds", "particle_steps_per_second",
                            "collisions_per_second", "output", "ranks"})
      j.erase(key);
    if (j.contains("analysis")) j["analysis"].erase("seconds");
    return j;
  }

  void expect_same_run(const std::string& a, const std::string& b, bool contacts = false) {
    std::vector<std::string> groups = {"/particles", "/observables", "/fields", "/analysis"};
    if (contacts) groups.insert(groups.end(), {"/connectivity", "/contacts"});
    for (const std::string& group : groups)
      EXPECT_TRUE(same_hdf5(dir_ / (a + ".h5"), dir_ / (b + ".h5"), group)) << group;
    EXPECT_EQ(without_timings(summary(a + ".json")), without_timings(summary(b + ".json")));
  }
};

TEST_F(Resume, KilledRunResumedIsBitIdenticalOnBothBackends) {
  struct Case {
    const char* scene;
    const char* backend;
    const char* sets;
    double kill_after;
  };
  for (const Case& c :
       {Case{"jet3d.ini", "soft_dem",
             "--set jet.grains=6000 --set run.t_end=30 --set analysis.window_start=5 "
             "--set analysis.window_end=30 "
             "--set output.fields=position,velocity,radius,id,omega,force,contacts",
             8.0},
        Case{"jet3d.ini", "event_driven",
             "--set jet.grains=20000 --set run.t_end=40 --set analysis.window_start=5 "
             "--set analysis.window_end=40",
             8.0}}) {
    const std::string base = "run " + scene(c.scene) + " --quiet --backend " + c.backend + " " +
                             c.sets + " --set run.checkpoint_interval=2 --set output.interval=1";
    const std::string straight = std::string("straight_") + c.backend;
    const std::string killed = std::string("killed_") + c.backend;
    ASSERT_EQ(granjet(base + paths(straight)), 0) << err_;
    const fs::path partial = dir_ / (killed + ".h5.partial");
    ASSERT_TRUE(run_and_kill(base + paths(killed), partial, c.kill_after))
        << c.backend << ": the run ended before it could be killed";
    EXPECT_FALSE(fs::exists(dir_ / (killed + ".h5")));
    if (std::string(c.backend) == "event_driven") {  // started as one of several MPI ranks
      ::setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
      const std::string before = bytes_of(partial);
      EXPECT_EQ(granjet("resume " + partial.string() + " --quiet"), 2);
      ::unsetenv("OMPI_COMM_WORLD_SIZE");
      EXPECT_NE(err_.find("granjet resume runs as one process: the event-driven backend"),
                std::string::npos)
          << err_;
      EXPECT_EQ(bytes_of(partial), before);
    }
    ASSERT_EQ(granjet("resume " + partial.string() + " --quiet --summary " +
                      (dir_ / (killed + ".json")).string()),
              0)
        << err_;
    EXPECT_FALSE(fs::exists(partial));
    expect_same_run(straight, killed, std::string(c.backend) == "soft_dem");
    // The resume appended to the killed run's log.
    std::ifstream in(dir_ / (killed + ".log"));
    const std::string log{std::istreambuf_iterator<char>(in), {}};
    const std::size_t resumed = log.find(" resume " + partial.string());
    EXPECT_NE(log.find(" run "), std::string::npos) << log;
    EXPECT_NE(resumed, std::string::npos) << log;
    EXPECT_NE(log.find("continuing ", resumed), std::string::npos) << log;
  }
}

// Killed while it wrote its next checkpoint: a half-written run.h5.checkpoint.partial lies beside
// the last complete checkpoint. The resume goes on from that one, gives the straight run, and
// the finished run leaves no checkpoint file behind.
TEST_F(Resume, KilledWhileWritingACheckpointResumesFromTheLastComplete) {
  const std::string base = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=3000 --set run.t_end=20"
                           " --set run.checkpoint_interval=2 --set output.interval=1"
                           " --set analysis.window_start=5 --set analysis.window_end=20";
  ASSERT_EQ(granjet(base + paths("straight")), 0) << err_;
  EXPECT_FALSE(fs::exists(analysis::checkpoint_path(dir_ / "straight.h5")));
  const fs::path partial = dir_ / "killed.h5.partial";
  ASSERT_TRUE(run_and_kill(base + paths("killed"), partial, 6.0));
  const fs::path checkpoint = analysis::checkpoint_path(partial);
  EXPECT_EQ(checkpoint, dir_ / "killed.h5.checkpoint");
  const double at = analysis::read_summary(partial).checkpoint_time;
  fs::path torn = checkpoint;
  torn += ".partial";
  const std::string whole = bytes_of(checkpoint);
  std::ofstream(torn, std::ios::binary) << whole.substr(0, whole.size() / 2);
  const analysis::FileSummary left = analysis::read_summary(partial);
  EXPECT_TRUE(left.checkpoint);
  EXPECT_EQ(left.checkpoint_time, at);
  ASSERT_EQ(granjet("resume " + partial.string() + " --quiet --summary " +
                    (dir_ / "killed.json").string()),
            0)
      << err_;
  expect_same_run("straight", "killed");
  EXPECT_FALSE(fs::exists(checkpoint));
  EXPECT_FALSE(fs::exists(torn));
}

// A .partial without its checkpoint (moved away, or a run killed before its first) is refused
// with the file it lacks named, and left as it was.
TEST_F(Resume, APartialWithoutItsCheckpointIsRefusedAndKept) {
  const std::string base = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=3000 --set run.t_end=20"
                           " --set run.checkpoint_interval=2 --set analysis.enabled=false";
  const fs::path partial = dir_ / "killed.h5.partial";
  ASSERT_TRUE(run_and_kill(base + paths("killed"), partial, 2.0));
  fs::remove(analysis::checkpoint_path(partial));
  EXPECT_FALSE(analysis::read_summary(partial).checkpoint);
  const std::string before = bytes_of(partial);
  EXPECT_EQ(granjet("resume " + partial.string() + " --quiet"), 2);
  EXPECT_NE(err_.find("has no checkpoint beside it (killed.h5.checkpoint)"), std::string::npos)
      << err_;
  EXPECT_EQ(bytes_of(partial), before);
}

// SIGINT, SIGTERM, SIGHUP: the run stops after its step, writes a checkpoint, keeps its
// .partial as "interrupted" with its summary, says how to resume, and exits 128 + the signal;
// resumed, it completes. A second signal exits at once, with the same code.
TEST_F(Resume, SignalsCheckpointAndExitWithTheirCode) {
  const std::string base = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=6000 --set run.t_end=30"
                           " --set run.checkpoint_interval=2 --set analysis.enabled=false";
  for (const auto& [signals, code] : std::vector<std::pair<std::vector<int>, int>>{
           {{SIGINT}, 130}, {{SIGTERM}, 143}, {{SIGHUP}, 129}, {{SIGTERM, SIGTERM}, 143}}) {
    // append(), not "literal" + string: GCC 12 reports a false -Wrestrict for the latter.
    const std::string name = std::string("s")
                                 .append(std::to_string(code))
                                 .append("_")
                                 .append(std::to_string(signals.size()));
    const fs::path partial = dir_ / (name + ".h5.partial");
    const int status = run_and_signal(base + " --out " + (dir_ / (name + ".h5")).string() +
                                          " --summary " + (dir_ / (name + ".json")).string(),
                                      partial, 2.0, signals);
    ASSERT_TRUE(status != -1 && WIFEXITED(status)) << name << " status " << status << err_;
    EXPECT_EQ(WEXITSTATUS(status), code) << name << err_;
    const analysis::FileSummary kept = analysis::read_summary(partial);
    EXPECT_TRUE(kept.checkpoint) << name;
    if (signals.size() > 1) continue;  // the second signal may come before the checkpoint
    EXPECT_EQ(kept.status, "interrupted");
    EXPECT_EQ(summary(name + ".json")["status"], "interrupted");
    EXPECT_NE(err_.find("granjet resume " + partial.string()), std::string::npos) << err_;
    ASSERT_EQ(granjet("resume " + partial.string() + " --quiet"), 0) << err_;
    const analysis::FileSummary done = analysis::read_summary(dir_ / (name + ".h5"));
    EXPECT_EQ(done.status, "complete");
    EXPECT_EQ(done.last_time, 30.0);
  }
}

// A run killed before its run.t_end = 12 and resumed with run.t_end = 20 is the run of 20.
TEST_F(Resume, ResumeMayExtendTheRunAndNothingElse) {
  const std::string base = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=6000 --set run.checkpoint_interval=2"
                           " --set analysis.enabled=false --set output.interval=1";
  ASSERT_EQ(granjet(base + " --set run.t_end=20 --out " + (dir_ / "long.h5").string()), 0) << err_;
  ASSERT_TRUE(run_and_kill(base + " --set run.t_end=12 --out " + (dir_ / "short.h5").string(),
                           dir_ / "short.h5.partial", 4.0));
  const std::string partial = (dir_ / "short.h5.partial").string();
  EXPECT_EQ(granjet("resume " + partial + " --set contact.friction=0"), 2);
  EXPECT_NE(err_.find("contact.friction: cannot change on resume"), std::string::npos) << err_;
  EXPECT_EQ(granjet("resume " + partial + " --set run.t_end=1"), 2);
  EXPECT_NE(err_.find("before the checkpoint"), std::string::npos) << err_;
  EXPECT_EQ(granjet("resume " + (dir_ / "long.h5").string()), 2);
  EXPECT_NE(err_.find("not a run's .partial"), std::string::npos) << err_;
  ASSERT_EQ(granjet("resume " + partial + " --quiet --set run.t_end=20"), 0) << err_;
  for (const char* group : {"/particles", "/observables"})
    EXPECT_TRUE(same_hdf5(dir_ / "long.h5", dir_ / "short.h5", group)) << group;
}

#ifdef GRANJET_HAS_MPI
// A run over two ranks, killed (kill -9, every rank) after a checkpoint that holds each rank's
// share of the grains apart, resumes on one process and over three ranks into the run one
// process makes straight through.
TEST_F(Resume, ACheckpointOverTwoRanksResumesOnOneProcessAndOverThree) {
  // To t = 16, killed after the checkpoint at t = 4: the kill has the rest of the run to come in
  // (to t = 8 the run sometimes ended first on a loaded machine, removing its checkpoint).
  const std::string base = small_jet3d_run("16") + " --set contact.friction=0.5";
  ASSERT_EQ(granjet(base + paths("straight")), 0) << err_;
  const fs::path partial = dir_ / "over2.h5.partial";
  // SIGKILL to mpiexec alone could leave its ranks running: every process whose command line
  // names the run's file goes.
  const int status = run_and_signal(base + paths("over2"), partial, 4.0, {}, mpiexec(2));
  ASSERT_NE(status, -1) << "the run ended before it could be killed";
  ASSERT_TRUE(fs::exists(analysis::checkpoint_path(partial)));
  for (const int ranks : {1, 3}) {
    const std::string name = "resumed_on" + std::to_string(ranks);
    fs::copy_file(partial, dir_ / (name + ".h5.partial"));
    fs::copy_file(analysis::checkpoint_path(partial), dir_ / (name + ".h5.checkpoint"));
    const std::string cmd = (ranks > 1 ? mpiexec(ranks) : std::string()) + GRANJET_BINARY +
                            " resume " + (dir_ / (name + ".h5.partial")).string() +
                            " --quiet --summary " + (dir_ / (name + ".json")).string() + " > " +
                            (dir_ / "resume.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << bytes_of(dir_ / "resume.txt");
    expect_same_run("straight", name, true);
  }
}

// A checkpoint written by one process resumes over two MPI ranks (mpirun -n 2 granjet resume)
// into the run one process makes straight through.
TEST_F(Resume, KilledRunResumesOverTwoRanks) {
  const std::string base = small_jet3d_run("12");
  ASSERT_EQ(granjet(base + paths("straight")), 0) << err_;
  const fs::path partial = dir_ / "killed.h5.partial";
  ASSERT_TRUE(run_and_kill(base + paths("killed"), partial, 4.0))
      << "the run ended before it could be killed";
  // A refused resume over ranks: the error once, every rank ended, the run kept as it was.
  const std::string before = bytes_of(partial);
  EXPECT_EQ(granjet_over_ranks(2, "resume " + partial.string() + " --set jet.grains=5 --quiet"), 2)
      << err_;
  EXPECT_NE(err_.find("jet.grains: cannot change on resume"), std::string::npos) << err_;
  EXPECT_EQ(err_.find("cannot change", err_.find("cannot change") + 1), std::string::npos) << err_;
  EXPECT_EQ(bytes_of(partial), before);
  const std::string cmd = mpiexec(2) + GRANJET_BINARY + " resume " + partial.string() +
                          " --quiet --summary " + (dir_ / "killed.json").string() + " > " +
                          (dir_ / "mpi.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << bytes_of(dir_ / "mpi.txt");
  EXPECT_FALSE(fs::exists(partial));
  expect_same_run("straight", "killed", true);
  EXPECT_EQ(summary("killed.json")["ranks"]["count"], 2);
}
#endif

}  // namespace
}  // namespace granjet
