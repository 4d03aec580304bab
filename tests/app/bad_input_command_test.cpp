// Inputs that could crash, hang, destroy a file or leave an incomplete file under its final
// name: each command exits 2 naming the key or option, writes nothing and leaves
// the input as it was, or gives a correct result.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "analysis/file_lock.hpp"
#include "analysis/h5md_writer.hpp"
#include "command_fixture.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

class BadInput : public testing::CommandTest {
 protected:
  // The directory's entries, to show that a refused command wrote nothing.
  std::set<fs::path> entries() const {
    std::set<fs::path> found;
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().filename() != "stdout.txt" && e.path().filename() != "stderr.txt")
        found.insert(e.path());
    return found;
  }
  static std::string text_of(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // Exit 2, `needle` in the message, and no file added or changed.
  void expect_refused(const std::string& args, const std::string& needle) {
    const std::set<fs::path> before = entries();
    EXPECT_EQ(granjet(args), 2) << args << "\n" << err_;
    EXPECT_NE(err_.find(needle), std::string::npos) << args << "\n" << err_;
    EXPECT_EQ(entries(), before) << args;
  }
};

// Started by mpirun as one of several ranks (as Open MPI tells its processes), an event-driven
// run and a comparison refuse before they write, saying why the event-driven backend runs as one
// process (an event-driven resume: Resume.KilledRunResumedIsBitIdenticalOnBothBackends).
TEST_F(BadInput, OneRunStartedOnSeveralMpiRanksIsRefused) {
  const fs::path copy = dir_ / "binary.ini";
  fs::copy_file(scene("binary.ini"), copy);
  const std::string out = " --out " + (dir_ / "a.h5").string();
  struct Launched {  // the launcher's variables, for this scope
    explicit Launched(const char* rank) {
      ::setenv("OMPI_COMM_WORLD_SIZE", "2", 1);
      ::setenv("OMPI_COMM_WORLD_RANK", rank, 1);
    }
    ~Launched() {
      ::unsetenv("OMPI_COMM_WORLD_SIZE");
      ::unsetenv("OMPI_COMM_WORLD_RANK");
    }
  };
  {
    const Launched launched("0");
    expect_refused("run " + copy.string() + " --backend event_driven" + out,
                   "the event-driven backend handles the collisions one at a time");
    expect_refused("compare " + copy.string() + " --out " + (dir_ / "both").string(),
                   "granjet compare runs as one process: the event-driven backend");
  }
  {  // the other ranks end alike and leave the naming to rank 0: one message in all
    const Launched launched("1");
    expect_refused("run " + copy.string() + " --backend event_driven" + out, "");
    EXPECT_EQ(err_, "");
  }
  EXPECT_EQ(granjet("run " + copy.string() + out + " --quiet"), 0) << err_;  // one rank runs
}

TEST_F(BadInput, OutputThatIsTheSceneOrTheOtherOutputIsRefused) {
  const fs::path copy = dir_ / "binary.ini";
  fs::copy_file(scene("binary.ini"), copy);
  const std::string original = text_of(copy);
  expect_refused("run " + copy.string() + " --out " + copy.string(), "is the input file");
  expect_refused("run " + copy.string() + " --summary " + copy.string(), "is the input file");
  EXPECT_EQ(text_of(copy), original);
  const std::string x = (dir_ / "x").string();
  expect_refused("run " + copy.string() + " --out " + x + " --summary " + x,
                 "would be both the run's summary and the run's file");
  // The XDMF sidecar of a.xmf would be a.xmf itself.
  expect_refused("run " + copy.string() + " --out " + (dir_ / "a.xmf").string(),
                 "XDMF sidecar and the run's file");
}

TEST_F(BadInput, OutputThatExistsAndIsNotARegularFileIsRefused) {
  fs::create_directory(dir_ / "taken");
  expect_refused("run " + scene("binary.ini") + " --out " + (dir_ / "taken").string(),
                 "not a regular file");
  // As root this used to replace the device node by an HDF5 file.
  expect_refused("run " + scene("binary.ini") + " --out /dev/null", "not a regular file");
  struct stat device {};
  ASSERT_EQ(::stat("/dev/null", &device), 0);
  EXPECT_TRUE(S_ISCHR(device.st_mode));
  expect_refused("run " + scene("binary.ini") + " --out " + (dir_ / "no/such/dir/x.h5").string(),
                 "no directory");
}

// A second run with the same --out used to truncate the first one's .partial, which then ended
// "complete" with an unreadable file.
TEST_F(BadInput, ABusyOutputIsRefusedAndLeftAlone) {
  const fs::path partial = dir_ / "x.h5.partial";
  std::ofstream(partial) << "the first run's frames";
  const analysis::FileLock first_run(partial);
  EXPECT_EQ(granjet("run " + scene("binary.ini") + " --quiet --out " + (dir_ / "x.h5").string()), 2)
      << err_;
  EXPECT_NE(err_.find("being written by another granjet run"), std::string::npos) << err_;
  EXPECT_EQ(text_of(partial), "the first run's frames");
  EXPECT_FALSE(fs::exists(dir_ / "x.h5"));
}

// A user watches a run: `info` reads its .partial while the writer holds it open.
TEST_F(BadInput, InfoReadsARunningPartial) {
  analysis::RunMetadata meta;
  meta.backend = "soft_dem";
  meta.scene_ini = "[scene]\nkind = binary\n";
  analysis::H5mdWriter<3> writer(dir_ / "run.h5", meta, 2);
  Particles<3> p;
  p.add(0, GrainKind::kFree, Vec<3>(0, 0, 0), Vec<3>(1, 0, 0), 0.5, 1.0);
  writer.write_frame(0, 0.0, p);
  ASSERT_EQ(granjet("info " + (dir_ / "run.h5.partial").string()), 0) << err_;
  EXPECT_NE(text_of(dir_ / "stdout.txt").find("status: running"), std::string::npos);
}

TEST_F(BadInput, SceneFilesThatAreNoScenesAreRefused) {
  std::ofstream(dir_ / "empty.ini").close();
  std::ofstream(dir_ / "twice.ini") << "[scene]\nkind = jet\nkind = binary\n";
  expect_refused("run " + (dir_ / "empty.ini").string(), "names no scene.kind");
  expect_refused("run " + dir_.string(), "not a regular file");
  expect_refused("run " + (dir_ / "twice.ini").string(), "lines 2 and 3");
}

TEST_F(BadInput, ValuesThatCrashedHungOrWrappedAreRefused) {
  const std::string jet = "run " + scene("jet3d.ini") + " --set ";
  expect_refused(jet + "run.threads=4294967296", "run.threads");
  expect_refused(jet + "run.threads=4294967298", "run.threads");
  expect_refused(jet + "analysis.lateral_bins=4294967297", "analysis.lateral_bins");
  expect_refused(jet + "jet.grains=500000000", "jet.grains");
  expect_refused(jet + "jet.phi_tilde=1e-308", "jet.phi_tilde");
  expect_refused(jet + "jet.spacing=1e308", "jet.spacing");
  expect_refused(jet + "output.interval=1e-17", "output.interval");
  expect_refused(jet + "run.dt=1e-308", "run.dt");
  expect_refused(jet + "run.skin=1e12", "run.skin");
  expect_refused("run " + scene("jet2d.ini") + " --set region.radius=10", "cuts the jet");
  const std::string gas = "run " + scene("gas3d.ini") + " --set ";
  expect_refused(gas + "gas.grains=9223372036854775807", "gas.grains");
  expect_refused(gas + "gas.phi=1e-308", "gas.phi");
  expect_refused(gas + "gas.temperature=1e308", "gas.temperature");
  expect_refused(gas + "gas.sample_interval=1e-17 --backend event_driven", "gas.sample_interval");
  expect_refused("run " + scene("binary.ini") + " --seeds 1..20000", "at most 10000");
}

// output.fields asks only for what the backend has, and the run is refused before it writes.
TEST_F(BadInput, OutputFieldsTheBackendCannotGiveAreRefused) {
  const std::string jet = "run " + scene("jet3d.ini") + " --set jet.grains=500 --set ";
  expect_refused(jet + "output.fields=position,velocity,radius,id,contacts --backend event_driven",
                 "impulses only");
  expect_refused(jet + "output.fields=position,velocity,radius,id,force --backend event_driven",
                 "output.fields");
  expect_refused(jet + "output.fields=position,velocity,radius,id,omega --backend event_driven",
                 "smooth hard spheres");
  expect_refused(jet + "output.fields=position,velocity,radius,id,omega --set contact.friction=0",
                 "contact.friction = 0");
}

// Valid runs that measure nothing used to end "complete" without a word.
TEST_F(BadInput, RunsThatMeasureNothingWarn) {
  const std::string out =
      " --quiet --out " + (dir_ / "w.h5").string() + " --summary " + (dir_ / "w.json").string();
  for (const auto& [set, warning] :
       {std::pair{"run.t_end=0.001", "shorter than one time step"},
        std::pair{"run.t_end=1", "ends before the analysis window"},
        std::pair{"wall.diameter=1.5 --set run.t_end=0.01", "a target of one grain"}}) {
    ASSERT_EQ(granjet("run " + scene("jet3d.ini") + " --set jet.grains=50 --set " + set + out), 0)
        << err_;
    EXPECT_NE(err_.find("granjet: warning: "), std::string::npos) << err_;
    EXPECT_NE(err_.find(warning), std::string::npos) << err_;
    const nlohmann::json warnings = summary("w.json")["warnings"];
    ASSERT_TRUE(warnings.is_array()) << set;
    EXPECT_NE(warnings.dump().find(warning), std::string::npos) << warnings.dump();
  }
  ASSERT_EQ(granjet("run " + scene("binary.ini") + out), 0) << err_;
  EXPECT_FALSE(summary("w.json").contains("warnings"));
}

// The range's end is the largest seed: the loop used to wrap around and grow without end.
TEST_F(BadInput, ASeedRangeEndingAtTheLargestSeedRunsOnce) {
  ASSERT_EQ(granjet("run " + scene("binary.ini") +
                    " --quiet --seeds 18446744073709551615..18446744073709551615 --out " +
                    (dir_ / "b.h5").string()),
            0)
      << err_;
  EXPECT_TRUE(fs::exists(dir_ / "b.seed18446744073709551615.h5"));
}

// A frame as a damaged or foreign file may hold it: analyze used to segfault on id -1 and
// accepted non-finite positions and negative radii.
TEST_F(BadInput, AnalyzeRefusesFramesWithImpossibleGrains) {
  struct Damage {
    const char* name;
    GrainId id;
    double x, radius;
    const char* message;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Damage& d :
       {Damage{"id", 1, 0.0, 0.5, "holds grain id 2"}, Damage{"nan", 1, nan, 0.5, "not finite"},
        Damage{"inf", 1, std::numeric_limits<double>::infinity(), 0.5, "not finite"},
        Damage{"radius", 1, 0.0, -0.5, "radius"}}) {
    const fs::path file = dir_ / (std::string(d.name) + ".h5");
    analysis::RunMetadata meta;
    meta.backend = "soft_dem";
    meta.dimension = 2;
    meta.scene_ini =
        "[scene]\nkind = jet\ndimension = 2\n[output]\ninterval = 1\n"
        "[analysis]\nwindow_start = 0\nwindow_end = 2\n";
    {
      analysis::H5mdWriter<2> writer(file, meta, 3);
      for (int frame = 0; frame < 3; ++frame) {
        Particles<2> p;
        p.add(0, GrainKind::kFree, Vec<2>(1.0, 0.0), Vec<2>(-1.0, 0.0), 0.5, 1.0);
        p.add(d.id, GrainKind::kFree, Vec<2>(d.x, 3.0), Vec<2>(-1.0, 0.0), d.radius, 1.0);
        p.add(2, GrainKind::kFree, Vec<2>(2.0, 50.0), Vec<2>(0.0, 1.0), 0.5, 1.0);
        writer.write_frame(frame, frame, p);
      }
      writer.finish();
    }
    if (std::string(d.name) == "id") {
      // A row that claims another grain: the writer never makes one, a damaged file may.
      const hid_t h5 = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      const hid_t set = H5Dopen2(h5, "/particles/all/id/value", H5P_DEFAULT);
      const std::int64_t wrong[3] = {0, 2, 2};
      const hsize_t start[2] = {0, 0}, count[2] = {1, 3};
      const hid_t space = H5Dget_space(set), memory = H5Screate_simple(2, count, nullptr);
      H5Sselect_hyperslab(space, H5S_SELECT_SET, start, nullptr, count, nullptr);
      ASSERT_GE(H5Dwrite(set, H5T_NATIVE_INT64, memory, space, H5P_DEFAULT, wrong), 0);
      H5Sclose(memory);
      H5Sclose(space);
      H5Dclose(set);
      H5Fclose(h5);
    }
    const auto before = fs::last_write_time(file);
    EXPECT_EQ(granjet("analyze " + file.string()), 2) << d.name << "\n" << err_;
    EXPECT_NE(err_.find(d.message), std::string::npos) << err_;
    EXPECT_EQ(fs::last_write_time(file), before) << d.name;
  }
}

}  // namespace
}  // namespace granjet
