// `granjet campaign` end to end on campaigns/smoke.ini (ten runs of a fraction of a second):
// merging, resuming after a kill, --jobs and MPI ranks giving the same files, a changed key
// rerunning only its group, malformed files refused, and the thesis campaign's dry run.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <thread>
#include <tuple>

#include "analysis/field_reader.hpp"
#include "analysis/file_lock.hpp"
#include "analysis/h5md_reader.hpp"
#include "command_fixture.hpp"

namespace granjet::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kCampaigns = fs::path(GRANJET_SCENES_DIR) / ".." / "campaigns";
const std::string kSmoke = (kCampaigns / "smoke.ini").string();
const std::string kOnlyJet3d = " --quiet --jobs 1 --only F5.3 --out ";

class CampaignCommand : public CommandTest {
 protected:
  // The run and ensemble files under `dir`, relative to it.
  static std::set<fs::path> h5_files(const fs::path& dir) {
    std::set<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      if (entry.path().extension() == ".h5") files.insert(fs::relative(entry.path(), dir));
    return files;
  }
  // Every HDF5 file of `a` has a twin in `b` with the same contents (h5diff: every dataset and
  // attribute, value for value).
  static void expect_same_files(const fs::path& a, const fs::path& b) {
    const std::set<fs::path> files = h5_files(a);
    EXPECT_EQ(files, h5_files(b));
    EXPECT_EQ(files.size(), 10u + 4u);  // ten runs, four analysed ensembles
    for (const fs::path& f : files) EXPECT_TRUE(same_hdf5(a / f, b / f)) << f;
  }
  nlohmann::json manifest(const fs::path& dir) const {
    std::ifstream in(dir / "manifest.json");
    return nlohmann::json::parse(in);
  }
  // A copy of smoke.ini in the test directory (scene paths made absolute), with `edit` applied.
  fs::path smoke_copy(const std::string& from = "", const std::string& to = "") const {
    std::ifstream in(kSmoke);
    std::stringstream s;
    s << in.rdbuf();
    std::string text = std::regex_replace(s.str(), std::regex(R"(\.\./scenes/)"),
                                          std::string(GRANJET_SCENES_DIR) + "/");
    if (!from.empty()) text.replace(text.find(from), from.size(), to);
    const fs::path file = dir_ / "smoke.ini";
    std::ofstream(file) << text;
    return file;
  }
  // smoke.ini whose jet3d group (F5.3: two seeds) runs a few seconds with a checkpoint every
  // time unit, long enough to be stopped on the way.
  fs::path long_jet3d() const {
    const fs::path file = smoke_copy("jet.grains = 300\njet.diameter = 4\nwall.diameter = 8",
                                     "jet.grains = 4000\njet.diameter = 16\nwall.diameter = 36\n"
                                     "run.checkpoint_interval = 1");
    std::string text;
    {
      std::ifstream in(file);
      text.assign(std::istreambuf_iterator<char>(in), {});
    }
    text.replace(text.find("region.radius = 16"), 18, "region.radius = 72");
    text.replace(text.find("run.t_end = 10"), 14, "run.t_end = 40");
    std::ofstream(file) << text;
    return file;
  }
  // Whether `partial` holds a checkpoint at `after` or later (false while it is written).
  static bool checkpointed(const fs::path& partial, double after) {
    try {
      const analysis::FileSummary s = analysis::read_summary(partial);
      return s.checkpoint && s.checkpoint_time >= after;
    } catch (const std::exception&) {
      return false;
    }
  }
  // Starts `granjet campaign FILE --quiet --jobs 1 --only F5.3 --out OUT` in the background.
  static pid_t start_campaign(const fs::path& file, const fs::path& out) {
    const pid_t pid = fork();
    if (pid == 0) {
      const std::string dir = out.string(), campaign = file.string();
      execl(GRANJET_BINARY, GRANJET_BINARY, "campaign", campaign.c_str(), "--quiet", "--jobs", "1",
            "--only", "F5.3", "--out", dir.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    return pid;
  }
  // long_jet3d's group F5.3 run straight into `straight`, then the same campaign started in the
  // background into `out`: its pid, or -1 when either failed.
  pid_t after_a_straight_campaign(const fs::path& file, const fs::path& straight,
                                  const fs::path& out) {
    if (granjet("campaign " + file.string() + kOnlyJet3d + straight.string()) != 0) return -1;
    return start_campaign(file, out);
  }
  // Calls `act` each time `partial` is seen to hold a checkpoint at t >= 3, until it returns
  // true (every 5 ms, for at most 30 s); whether it did.
  template <class Act>
  static bool once_checkpointed(const fs::path& partial, Act act) {
    for (int tries = 0; tries < 6000; ++tries) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      if (checkpointed(partial, 3.0) && act()) return true;
    }
    return false;
  }
  static void expect_same_jet3d(const fs::path& a, const fs::path& b) {
    for (const char* f : {"jet3d.seed1.h5", "jet3d.seed2.h5", "jet3d.h5"})
      EXPECT_TRUE(same_hdf5(a / "jet3d" / f, b / "jet3d" / f))
          << f << ":\n"
          << hdf5_differences(a / "jet3d" / f, b / "jet3d" / f);
  }
};

TEST_F(CampaignCommand, SmokeRunsEveryRunMergesEachEnsembleAsRunSeedsDoesAndSkipsWhatIsDone) {
  const fs::path out = dir_ / "a";
  ASSERT_EQ(granjet("campaign " + kSmoke + " --out " + out.string() + " --jobs 2"), 0) << err_;
  const nlohmann::json m = manifest(out);
  EXPECT_EQ(m["campaign"], "smoke");
  ASSERT_EQ(m["runs"].size(), 10u);
  for (const auto& [name, run] : m["runs"].items()) {
    EXPECT_EQ(run["status"], "complete") << name;
    EXPECT_TRUE(fs::exists(run["output"].get<std::string>())) << name;
    EXPECT_FALSE(run["host"].get<std::string>().empty());
  }
  EXPECT_EQ(m["ensembles"]["jet2d/friction-0.2"]["combined"], 2);
  EXPECT_TRUE(analysis::has_analysis(out / "jet3d" / "jet3d.h5"));

  // The ensemble is the one `granjet run --seeds` makes of the same scene.
  const fs::path member_ini = out / "jet2d" / "friction-0.2.seed1.ini";
  ASSERT_EQ(granjet("run " + member_ini.string() + " --seeds 1..2 --quiet --out " +
                    (dir_ / "seeds.h5").string()),
            0)
      << err_;
  // The ensemble files differ only in the names of their members.
  for (const auto& [mine, theirs, object] :
       {std::tuple{dir_ / "seeds.h5", out / "jet2d" / "friction-0.2.h5", "/fields"},
        std::tuple{dir_ / "seeds.h5", out / "jet2d" / "friction-0.2.h5", "/analysis"},
        std::tuple{dir_ / "seeds.seed2.h5", out / "jet2d" / "friction-0.2.seed2.h5", "/"}})
    EXPECT_TRUE(same_hdf5(mine, theirs, object)) << theirs << " " << object;

  // Run again: nothing runs, nothing is rewritten.
  const auto stamp = fs::last_write_time(out / "jet3d" / "jet3d.seed1.h5");
  const auto merged = fs::last_write_time(out / "jet3d" / "jet3d.h5");
  ASSERT_EQ(granjet("campaign " + kSmoke + " --out " + out.string() + " --jobs 2"), 0) << err_;
  const nlohmann::json again = manifest(out);
  ASSERT_EQ(again["invocations"].size(), 2u);
  EXPECT_EQ(again["invocations"][1]["executed"], 0);
  EXPECT_EQ(again["invocations"][1]["found_complete"], 10);
  EXPECT_EQ(fs::last_write_time(out / "jet3d" / "jet3d.seed1.h5"), stamp);
  EXPECT_EQ(fs::last_write_time(out / "jet3d" / "jet3d.h5"), merged);
}

TEST_F(CampaignCommand, KilledCampaignRerunFinishesOnlyTheRestWithTheSameFiles) {
  const fs::path killed = dir_ / "killed", straight = dir_ / "straight";
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --jobs 1 --out " + straight.string()), 0);

  // Kill -9 the campaign and its running child once a few runs are complete.
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    setsid();
    const std::string out = killed.string();
    execl(GRANJET_BINARY, GRANJET_BINARY, "campaign", kSmoke.c_str(), "--quiet", "--jobs", "1",
          "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int complete = 0;
  for (int tries = 0; tries < 6000 && complete < 3; ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    try {
      const nlohmann::json m = manifest(killed);
      complete = 0;
      for (const auto& [name, run] : m["runs"].items()) complete += run["status"] == "complete";
    } catch (const std::exception&) {  // not written yet
    }
  }
  kill(-pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  ASSERT_GE(complete, 3);
  ASSERT_LT(complete, 10) << "the campaign ended before it could be killed";
  std::size_t done_before = 0;
  const nlohmann::json at_kill = manifest(killed);
  for (const auto& [name, run] : at_kill["runs"].items())
    done_before += run["status"] == "complete";

  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --jobs 1 --out " + killed.string()), 0)
      << err_;
  const nlohmann::json m = manifest(killed);
  EXPECT_EQ(m["invocations"][1]["found_complete"].get<std::size_t>(), done_before);
  EXPECT_EQ(m["invocations"][1]["executed"].get<std::size_t>(), 10u - done_before);
  expect_same_files(killed, straight);
}

// Ctrl-C (SIGINT to the campaign alone: its runs have process groups of their own): no run
// starts any more, the running one stops at its last scheduled checkpoint and is recorded as
// interrupted, the campaign exits 130; run again, it resumes that run from its checkpoint, and
// every file is the one a campaign never stopped writes. Meanwhile a second campaign in the same
// DIR is refused, and --status says where it stands.
TEST_F(CampaignCommand, InterruptedCampaignResumesItsRunsToTheSameFiles) {
  const fs::path file = long_jet3d();
  const fs::path straight = dir_ / "straight", stopped = dir_ / "stopped";
  const pid_t pid = after_a_straight_campaign(file, straight, stopped);
  ASSERT_GE(pid, 0) << err_;
  const fs::path partial = stopped / "jet3d" / "jet3d.seed1.h5.partial";
  const bool sent = once_checkpointed(partial, [&] {
    // One campaign per DIR: a second one is refused while the first runs.
    EXPECT_EQ(granjet("campaign " + file.string() + kOnlyJet3d + stopped.string()), 2);
    EXPECT_NE(err_.find("is being run by another granjet campaign"), std::string::npos) << err_;
    EXPECT_EQ(granjet("campaign " + file.string() + " --status --out " + stopped.string()), 0);
    return kill(pid, SIGINT) == 0;
  });
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(sent) << "the run ended before its campaign could be interrupted";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  nlohmann::json m = manifest(stopped);
  EXPECT_EQ(m["runs"]["jet3d/jet3d.seed1"]["status"], "interrupted");
  EXPECT_NE(m["runs"]["jet3d/jet3d.seed2"]["status"], "complete");  // never started
  EXPECT_TRUE(analysis::read_summary(partial).checkpoint);
  ASSERT_EQ(granjet("campaign " + file.string() + " --status --out " + stopped.string()), 0);
  std::ifstream report(dir_ / "stdout.txt");
  const std::string said{std::istreambuf_iterator<char>(report), {}};
  EXPECT_NE(said.find("not running"), std::string::npos) << said;
  EXPECT_NE(said.find("jet3d/jet3d.seed1: interrupted (exit code 130"), std::string::npos) << said;

  ASSERT_EQ(granjet("campaign " + file.string() + kOnlyJet3d + stopped.string()), 0) << err_;
  m = manifest(stopped);
  EXPECT_EQ(m["runs"]["jet3d/jet3d.seed1"]["status"], "complete");
  std::ifstream log(stopped / "jet3d" / "jet3d.seed1.log");
  const std::string logged{std::istreambuf_iterator<char>(log), {}};
  EXPECT_NE(logged.find("continuing "), std::string::npos) << "resumed, not run again";
  expect_same_jet3d(straight, stopped);
}

// kill -9 of a run (the out-of-memory killer, an operator): the run goes back to the queue once,
// resumes from its checkpoint, and the campaign ends complete with the files of one never hit.
TEST_F(CampaignCommand, AKilledRunGoesBackToTheQueueAndResumes) {
  const fs::path file = long_jet3d();
  const fs::path straight = dir_ / "straight", hit = dir_ / "hit";
  const pid_t pid = after_a_straight_campaign(file, straight, hit);
  ASSERT_GE(pid, 0) << err_;
  // This campaign's run only, not another test's: [.] keeps the pattern from matching the shell
  // that runs pkill.
  const std::string kill =
      "pkill -KILL -f 'run " + (hit / "jet3d").string() + "/jet3d[.]seed1[.]ini'";
  const bool killed = once_checkpointed(hit / "jet3d" / "jet3d.seed1.h5.partial",
                                        [&] { return std::system(kill.c_str()) == 0; });
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(killed) << "the run ended before it could be killed";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const nlohmann::json entry = manifest(hit)["runs"]["jet3d/jet3d.seed1"];
  EXPECT_EQ(entry["status"], "complete");
  std::ifstream log(hit / "jet3d" / "jet3d.seed1.log");
  const std::string logged{std::istreambuf_iterator<char>(log), {}};
  EXPECT_NE(logged.find("continuing "), std::string::npos)
      << "resumed, not run again; its log:\n"
      << logged << "its manifest entry: " << entry.dump();
  expect_same_jet3d(straight, hit);
}

// A .partial that a resume cannot use (here a dataset the writer reopens is gone, as a kill in
// the middle of HDF5's writes could leave it) does not hold the campaign up at every
// invocation: the run starts again from t = 0, once, says why, and the files are those of a
// campaign never hit.
TEST_F(CampaignCommand, ARunWhoseResumeFailsStartsAgainFromTheStart) {
  const fs::path file = long_jet3d();
  const fs::path straight = dir_ / "straight", hit = dir_ / "hit";
  const pid_t pid = after_a_straight_campaign(file, straight, hit);
  ASSERT_GE(pid, 0) << err_;
  const fs::path partial = hit / "jet3d" / "jet3d.seed1.h5.partial";
  // The campaign, and with it its run (PR_SET_PDEATHSIG).
  const bool killed = once_checkpointed(partial, [&] { return kill(pid, SIGKILL) == 0; });
  waitpid(pid, nullptr, 0);
  ASSERT_TRUE(killed) << "the run ended before it could be killed";
  // The run dies just after its campaign: its lock on the .partial goes with it.
  for (int tries = 0; tries < 1000 && analysis::FileLock::held(partial); ++tries)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  {
    const hid_t h5 = H5Fopen(partial.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(h5, 0);
    EXPECT_GE(H5Ldelete(h5, "/observables/dt", H5P_DEFAULT), 0);
    H5Fclose(h5);
  }
  ASSERT_TRUE(analysis::read_summary(partial).checkpoint);  // it looks resumable
  ASSERT_EQ(granjet("campaign " + file.string() + kOnlyJet3d + hit.string()), 0) << err_;
  std::ifstream report(dir_ / "stdout.txt");
  const std::string said{std::istreambuf_iterator<char>(report), {}};
  EXPECT_NE(said.find("jet3d/jet3d.seed1  could not be resumed ("), std::string::npos) << said;
  EXPECT_NE(said.find("/observables/dt"), std::string::npos) << said;
  EXPECT_NE(said.find("starts again from t = 0"), std::string::npos) << said;
  EXPECT_EQ(manifest(hit)["runs"]["jet3d/jet3d.seed1"]["status"], "complete");
  expect_same_jet3d(straight, hit);
}

TEST_F(CampaignCommand, OneJobTwoJobsAndTwoMpiRanksGiveTheSameFiles) {
  const fs::path one = dir_ / "one", two = dir_ / "two";
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --jobs 1 --out " + one.string()), 0);
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --jobs 2 --out " + two.string()), 0);
  expect_same_files(one, two);
#ifdef GRANJET_HAS_MPI
  // Root needs --allow-run-as-root; two ranks on a machine of any size need --oversubscribe.
  const fs::path mpi = dir_ / "mpi";
  const std::string cmd = std::string(GRANJET_MPIEXEC) +
                          " --allow-run-as-root --oversubscribe -n 2 " + GRANJET_BINARY +
                          " campaign " + kSmoke + " --quiet --out " + mpi.string() + " > " +
                          (dir_ / "mpi.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  expect_same_files(one, mpi);
  const nlohmann::json m = manifest(mpi);
  std::set<int> ranks;
  for (const auto& [name, run] : m["runs"].items()) ranks.insert(run["rank"].get<int>());
  EXPECT_EQ(ranks, (std::set<int>{0, 1})) << "both ranks take runs";
  EXPECT_EQ(m["invocations"][0]["ranks"], 2);
#endif
}

#ifdef GRANJET_HAS_MPI
// The MPI rank (1) among the processes running `pattern`, by its Open MPI environment; 0: none.
pid_t rank_one(const std::string& pattern) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream cmdline(entry.path() / "cmdline"), environ(entry.path() / "environ");
    const std::string command{std::istreambuf_iterator<char>(cmdline), {}};
    const std::string env{std::istreambuf_iterator<char>(environ), {}};
    if (command.find(pattern) != std::string::npos &&
        env.find(std::string("OMPI_COMM_WORLD_RANK=1") + '\0') != std::string::npos)
      return static_cast<pid_t>(std::stol(name));
  }
  return 0;
}

// kill -9 of an MPI rank mid-campaign: Open MPI ends the whole job (its default), rank 0 stops
// its run at its checkpoint, the dead rank's run dies with it; run again (here on one process),
// the campaign resumes both and its files are those of a campaign never hit.
TEST_F(CampaignCommand, ALostMpiRankEndsTheJobAndARerunFinishesIt) {
  const fs::path file = long_jet3d();
  const fs::path straight = dir_ / "straight", hit = dir_ / "hit";
  ASSERT_EQ(granjet("campaign " + file.string() + kOnlyJet3d + straight.string()), 0) << err_;
  const std::string cmd = std::string(GRANJET_MPIEXEC) + " --allow-run-as-root --oversubscribe " +
                          "-n 2 " + GRANJET_BINARY + " campaign " + file.string() +
                          " --quiet --only F5.3 --out " + hit.string() + " > " +
                          (dir_ / "mpi.txt").string() + " 2>&1";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  bool killed = false;
  for (int tries = 0; tries < 6000 && !killed; ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (!checkpointed(hit / "jet3d" / "jet3d.seed1.h5.partial", 2.0) ||
        !checkpointed(hit / "jet3d" / "jet3d.seed2.h5.partial", 2.0))
      continue;
    if (const pid_t rank = rank_one("campaign"); rank > 0) killed = kill(rank, SIGKILL) == 0;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(killed) << "the runs ended before a rank could be killed";
  EXPECT_NE(WEXITSTATUS(status), 0);  // the job ended
  ASSERT_EQ(granjet("campaign " + file.string() + kOnlyJet3d + hit.string()), 0) << err_;
  expect_same_jet3d(straight, hit);
}
#endif

TEST_F(CampaignCommand, AChangedKeyRerunsOnlyItsGroup) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(granjet("campaign " + smoke_copy().string() + " --quiet --out " + out.string()), 0);
  const auto stamp = fs::last_write_time(out / "jet2d" / "friction-0.seed1.h5");
  const std::string hard2d = "backend = event_driven\n";
  ASSERT_EQ(granjet("campaign " + smoke_copy(hard2d, hard2d + "ed.v0 = 0.2\n").string() +
                    " --quiet --out " + out.string()),
            0)
      << err_;
  const nlohmann::json m = manifest(out);
  EXPECT_EQ(m["invocations"][1]["executed"], 2);
  EXPECT_EQ(m["invocations"][1]["found_complete"], 8);
  EXPECT_EQ(m["runs"]["hard2d/hard2d.seed1"]["overrides"][0], "ed.v0=0.2");
  EXPECT_EQ(fs::last_write_time(out / "jet2d" / "friction-0.seed1.h5"), stamp);
}

// A run recorded under the scene hash of an older granjet (one that knew fewer keys) whose file
// holds this very run: found complete, its manifest entry keeps its history (times, host) and
// takes the current hash.
TEST_F(CampaignCommand, AnEntryUnderAnOlderHashKeepsItsHistory) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --out " + out.string()), 0);
  nlohmann::json m = manifest(out);
  const std::string name = "jet2d/friction-0.seed1";
  const std::string current = m["runs"][name]["hash"];
  m["runs"][name]["hash"] = "0123456789abcdef";
  m["runs"][name]["wall_seconds"] = 123.5;
  m["runs"][name]["host"] = "elsewhere";
  std::ofstream(out / "manifest.json") << m.dump(1);
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --out " + out.string()), 0) << err_;
  m = manifest(out);
  EXPECT_EQ(m["invocations"][1]["found_complete"], 10);
  EXPECT_EQ(m["invocations"][1]["executed"], 0);
  EXPECT_EQ(m["runs"][name]["hash"], current);
  EXPECT_EQ(m["runs"][name]["wall_seconds"], 123.5);
  EXPECT_EQ(m["runs"][name]["host"], "elsewhere");
}

// Stores `scene` as the file's /parameters/granjet/scene (a fixed-length string, as written).
void store_scene(const fs::path& file, const std::string& scene) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Ldelete(f, "/parameters/granjet/scene", H5P_DEFAULT);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, scene.size() + 1);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t set = H5Dcreate2(f, "/parameters/granjet/scene", type, space, H5P_DEFAULT,
                               H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, scene.c_str());
  H5Dclose(set);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(f);
}

// Upgrades: a run whose file an older granjet wrote, without the keys added since (their
// defaults keep the old physics), is still done, and --dry-run says so; a changed key makes
// --dry-run name the runs it would redo, with the key's old and new value.
TEST_F(CampaignCommand, DryRunSaysWhatAnUpgradeOrAChangedKeyWouldRedo) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(granjet("campaign " + kSmoke + " --quiet --out " + out.string()), 0);
  const fs::path old_file = out / "jet2d" / "friction-0.seed1.h5";
  std::string scene = analysis::read_summary(old_file).scene_ini;
  for (const std::string added : {"rolling_friction = 0\n", "adhesion = 0\n"}) {
    ASSERT_NE(scene.find(added), std::string::npos) << added;
    scene.erase(scene.find(added), added.size());
  }
  store_scene(old_file, scene);
  ASSERT_EQ(granjet("campaign " + kSmoke + " --dry-run --out " + out.string()), 0) << err_;
  std::ifstream said(dir_ / "stdout.txt");
  const std::string dry{std::istreambuf_iterator<char>(said), {}};
  EXPECT_NE(dry.find("10 of 10 runs done; the next invocation runs 0"), std::string::npos) << dry;

  const std::string hard2d = "backend = event_driven\n";
  ASSERT_EQ(granjet("campaign " + smoke_copy(hard2d, hard2d + "ed.v0 = 0.2\n").string() +
                    " --dry-run --out " + out.string()),
            0)
      << err_;
  std::ifstream said_again(dir_ / "stdout.txt");
  const std::string changed{std::istreambuf_iterator<char>(said_again), {}};
  EXPECT_NE(changed.find("8 of 10 runs done; the next invocation runs 2; 2 its file holds another "
                         "scene"),
            std::string::npos)
      << changed;
  EXPECT_NE(changed.find("hard2d/hard2d.seed1: its file holds another scene: ed.v0 0.1 -> 0.2"),
            std::string::npos)
      << changed;
}

TEST_F(CampaignCommand, MalformedCampaignExitsTwoNamingGroupAndKeyAndWritesNothing) {
  const fs::path out = dir_ / "out";
  const fs::path file = smoke_copy("contact.friction = 0, 0.2", "contact.friction = 0, -0.2");
  EXPECT_EQ(granjet("campaign " + file.string() + " --out " + out.string()), 2);
  EXPECT_NE(err_.find("[jet2d] contact.friction"), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(granjet("campaign " + kSmoke + " --only F9.9 --out " + out.string()), 2);
  EXPECT_NE(err_.find("--only"), std::string::npos) << err_;
  EXPECT_EQ(granjet("campaign " + kSmoke + " --jobs -1 --out " + out.string()), 2);
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CampaignCommand, ThesisDryRunListsEveryResultOfTheSpecWithItsRunsAndCost) {
  const fs::path out = dir_ / "out";
  ASSERT_EQ(granjet("campaign " + (kCampaigns / "thesis.ini").string() + " --dry-run --out " +
                    out.string()),
            0)
      << err_;
  EXPECT_FALSE(fs::exists(out));
  std::ifstream in(dir_ / "stdout.txt");
  std::stringstream s;
  s << in.rdbuf();
  const std::string listing = s.str();
  // model §7, every id.
  for (const char* id :
       {"T4.1", "F4.2", "F4.3", "F5.3", "F5.4", "F5.5", "F5.6", "T5.1", "F5.7", "T5.2", "F5.9",
        "F6.3", "F6.4", "F6.5", "F6.7", "F6.11-F6.14", "F6.16-F6.18", "FE.1", "HC"}) {
    // The id's row: its groups, a run count and a cost.
    std::string pattern = "\n";
    for (const char* c = id; *c; ++c)
      pattern += *c == '.' ? std::string("\\.") : std::string(1, *c);
    const std::regex row(pattern + " +[^ ]+ +[1-9][0-9]* +[0-9.e+]+");
    EXPECT_TRUE(std::regex_search(listing, row)) << id;
  }
  EXPECT_NE(listing.find("wall time on"), std::string::npos);
}

}  // namespace
}  // namespace granjet::testing
