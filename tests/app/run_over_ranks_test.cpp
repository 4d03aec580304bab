// `mpirun -n 2 granjet run` writes the file one process writes, dataset for dataset (h5diff):
// frames with forces and contacts, energies, inline analysis and a checkpoint, from a jet with
// friction on the tethered target. Its `--profile` gives each phase's spread over the ranks.
// Bad input, and the commands that run as one process, end every rank with one message.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "command_fixture.hpp"

namespace granjet::testing {
namespace {

namespace fs = std::filesystem;

class RunOverRanks : public CommandTest {};

#ifdef GRANJET_HAS_MPI
TEST_F(RunOverRanks, TwoRanksWriteTheFileOfOne) {
  const std::string sets =
      " --set jet.grains=2000 --set wall.diameter=14 --set run.t_end=3 --set output.interval=1"
      " --set run.checkpoint_interval=1 --set analysis.window_start=1 --set analysis.window_end=3"
      " --set output.fields=position,velocity,radius,id,omega,force,contacts --quiet --no-log";
  const std::string one = (dir_ / "one.h5").string(), two = (dir_ / "two.h5").string();
  ASSERT_EQ(granjet("run " + scene("jet3d.ini") + sets + " --out " + one), 0) << err_;
  // Root needs --allow-run-as-root; two ranks on a machine of any size need --oversubscribe.
  const std::string cmd =
      std::string(GRANJET_MPIEXEC) + " --allow-run-as-root --oversubscribe -n 2 " + GRANJET_BINARY +
      " run " + scene("jet3d.ini") + sets + " --profile --summary " + (dir_ / "two.json").string() +
      " --out " + two + " > " + (dir_ / "mpi.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_TRUE(same_hdf5(one, two));
  std::ifstream in(dir_ / "two.json");
  const nlohmann::json profile = nlohmann::json::parse(in)["profile"];
  EXPECT_EQ(profile["ranks"], 2);
  bool ghosts = false;
  for (const nlohmann::json& p : profile["phases"]) {
    const nlohmann::json& r = p["over_ranks"];
    EXPECT_LE(r["fastest"].get<double>(), r["mean"].get<double>()) << p["name"];
    EXPECT_LE(r["mean"].get<double>(), r["slowest"].get<double>()) << p["name"];
    EXPECT_LE(p["seconds"].get<double>(), r["slowest"].get<double>()) << p["name"];  // rank 0's
    if (p["name"] == "ranks: ghost states") {
      ghosts = true;
      EXPECT_GT(r["fastest"].get<double>(), 0.0) << "the other rank's profile is not in";
    }
  }
  EXPECT_TRUE(ghosts);
}

// How often `what` occurs in `text`.
std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Bad input over ranks ends every rank with the error named once and the bad-input exit code:
// an unknown key, found on every rank, an output directory that does not exist, which only
// rank 0 checks (the others used to wait for it forever), the event-driven backend, which
// every rank refuses before MPI starts, and a periodic box on the soft DEM (the ranks used to
// abort each other at the simulator's start, and no rank named it). No rank aborts the others
// before the message is out, and nothing is written.
TEST_F(RunOverRanks, BadInputEndsEveryRankWithOneMessage) {
  const std::string run = "run " + scene("jet3d.ini") + " --quiet --no-log";
  const fs::path out = dir_ / "bad.h5";
  struct Case {
    std::string args, message;
  };
  for (const Case& c :
       {Case{run + " --set run.no_such_key=1 --out " + out.string(),
             "run.no_such_key: unknown key"},
        Case{run + " --out " + (dir_ / "missing" / "bad.h5").string(), "no directory"},
        Case{run + " --backend event_driven --out " + out.string(),
             "the event-driven backend handles the collisions"},
        Case{"run " + scene("gas3d.ini") + " --backend soft_dem --quiet --no-log --out " +
                 out.string(),
             "mpirun -n 2: a periodic box runs on one rank"}}) {
    EXPECT_EQ(granjet_over_ranks(2, c.args), 2) << err_;
    EXPECT_EQ(occurrences(err_, c.message), 1u) << err_;
    EXPECT_EQ(err_.find("MPI_ABORT"), std::string::npos) << err_;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir_ / "bad.h5.partial"));
}

// The commands that read a finished run, info and analyze, run as one process: over ranks they
// used to run once on each rank, info printing everything K times and analyze racing itself for
// the file. Now every rank refuses before it reads the file: the reason once, the bad-input exit
// code, the file as it was and nothing written beside it.
TEST_F(RunOverRanks, CommandsOfOneProcessRefuseSeveralRanks) {
  const fs::path run = dir_ / "jet.h5";
  ASSERT_EQ(granjet("run " + scene("jet2d.ini") + " --set run.t_end=2 --quiet --no-log --out " +
                    run.string()),
            0)
      << err_;
  const std::string before = bytes_of(run);
  const std::size_t files = std::distance(fs::directory_iterator(dir_), fs::directory_iterator());
  for (const std::string command : {"info", "analyze"}) {
    EXPECT_EQ(granjet_over_ranks(2, command + " " + run.string()), 2) << err_;
    EXPECT_EQ(occurrences(err_, "mpirun -n 2: granjet " + command + " runs as one process"), 1u)
        << err_;
    EXPECT_EQ(err_.find("MPI_ABORT"), std::string::npos) << err_;
    EXPECT_EQ(err_.find("status:"), std::string::npos) << "info printed: " << err_;
  }
  EXPECT_EQ(bytes_of(run), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()),
            static_cast<std::ptrdiff_t>(files + 1))  // and mpiexec's own output
      << "analyze wrote beside the run";
}
#endif

}  // namespace
}  // namespace granjet::testing
