// The granjet command end to end: exit codes, outputs that are complete or clearly partial,
// the binary scene's measured restitution, and bit-identical reruns.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <vector>

#include "analysis/field_reader.hpp"
#include "analysis/h5md_reader.hpp"
#include "command_fixture.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

using GranjetCommand = testing::CommandTest;

TEST_F(GranjetCommand, BinarySceneReportsMeasuredRestitutionAndContactTime) {
  const fs::path out = dir_ / "b.h5", summary = dir_ / "b.json";
  ASSERT_EQ(granjet("run " + scene("binary.ini") + " --quiet --out " + out.string() +
                    " --summary " + summary.string()),
            0)
      << err_;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(dir_ / "b.xmf"));
  EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  std::ifstream in(summary);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["backend"], "soft_dem");
  EXPECT_EQ(j["dimension"], 3);
  EXPECT_EQ(j["grains"], 2);
  EXPECT_GT(j["steps"].get<int>(), 0);
  EXPECT_GT(j["particle_steps_per_second"].get<double>(), 0.0);
  // One thread: the loop's CPU time is positive and no more than its wall time.
  EXPECT_GT(j["cpu_seconds"].get<double>(), 0.0);
  EXPECT_LE(j["cpu_seconds"].get<double>(), j["wall_seconds"].get<double>() + 1e-3);
  EXPECT_NEAR(j["measured"]["restitution"].get<double>() / 0.75, 1.0, 0.005);
  EXPECT_NEAR(j["measured"]["contact_time"].get<double>() / 0.1, 1.0, 0.005);
}

TEST_F(GranjetCommand, SameSceneAndSeedGiveBitIdenticalFrames) {
  const std::string args =
      "run " + scene("jet3d.ini") +
      " --quiet --set jet.grains=400 --set run.t_end=4 --set output.interval=2";
  ASSERT_EQ(granjet(args + " --out " + (dir_ / "a.h5").string()), 0) << err_;
  ASSERT_EQ(granjet(args + " --out " + (dir_ / "b.h5").string()), 0) << err_;
  ASSERT_EQ(granjet(args + " --set run.seed=2 --out " + (dir_ / "c.h5").string()), 0) << err_;
  const auto a = analysis::read_frame<3>(dir_ / "a.h5", 2);
  const auto b = analysis::read_frame<3>(dir_ / "b.h5", 2);
  const auto c = analysis::read_frame<3>(dir_ / "c.h5", 2);
  ASSERT_FALSE(a.position.empty());
  EXPECT_EQ(a.id, b.id);
  EXPECT_TRUE(a.position == b.position);  // bit for bit
  EXPECT_TRUE(a.velocity == b.velocity);
  EXPECT_FALSE(a.position == c.position);
}

// HDF5 keeps the space of deleted objects: a complete run is copied without its checkpoint, so
// checkpoints cost nothing in the finished file (they would add about a quarter on jet3d).
TEST_F(GranjetCommand, CompleteRunFileIsNoBiggerForItsCheckpoints) {
  const std::string args = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=3000 --set run.t_end=6"
                           " --set output.interval=2 --set run.checkpoint_interval=";
  ASSERT_EQ(granjet(args + "1 --out " + (dir_ / "with.h5").string()), 0) << err_;
  ASSERT_EQ(granjet(args + "0 --out " + (dir_ / "without.h5").string()), 0) << err_;
  EXPECT_FALSE(analysis::read_summary(dir_ / "with.h5").checkpoint);
  EXPECT_LE(std::filesystem::file_size(dir_ / "with.h5"),
            std::filesystem::file_size(dir_ / "without.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "with.h5.compact"));
  EXPECT_EQ(analysis::read_frame<3>(dir_ / "with.h5", 3).id.size(),
            analysis::read_frame<3>(dir_ / "without.h5", 3).id.size());
}

TEST_F(GranjetCommand, AnalysisWindowThatNeverStartsSaysSoAndWritesNoFields) {
  const fs::path out = dir_ / "early.h5", summary = dir_ / "early.json";
  ASSERT_EQ(granjet("run " + scene("jet3d.ini") +
                    " --quiet --set jet.grains=300 --set run.t_end=4 --set analysis.window_start=8"
                    " --set analysis.window_end=16 --out " +
                    out.string() + " --summary " + summary.string()),
            0)
      << err_;
  EXPECT_NE(err_.find("ends before the analysis window 8..16 starts"), std::string::npos) << err_;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_FALSE(analysis::has_analysis(out));
  EXPECT_FALSE(fs::exists(dir_ / "early.fields.xmf"));
  std::ifstream in(summary);
  EXPECT_FALSE(nlohmann::json::parse(in).contains("analysis"));
}

TEST_F(GranjetCommand, BadInputExitsTwoNamingTheKeyAndWritesNothing) {
  const fs::path out = dir_ / "bad.h5";
  for (const std::string set :
       {"contact.restitution=1.5", "contact.contact_time=0", "contact.friction=-1", "run.dt=0.1",
        "jet.phi_tilde=2", "jet.colour=red", "run.threads=0"}) {
    EXPECT_EQ(granjet("run " + scene("jet3d.ini") + " --set " + set + " --out " + out.string()), 2);
    EXPECT_NE(err_.find(set.substr(0, set.find('='))), std::string::npos) << err_;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(out.string() + ".partial"));
  }
  EXPECT_EQ(granjet("run " + (dir_ / "missing.ini").string()), 2);
  EXPECT_NE(err_.find("missing.ini"), std::string::npos) << err_;
  EXPECT_EQ(granjet("run " + scene("jet3d.ini") + " --backend nonsense"), 2);
  EXPECT_NE(err_.find("--backend"), std::string::npos) << err_;
  EXPECT_EQ(granjet("frobnicate"), 2);
}

// --version names the commit it was built from (run/commit.cmake; "unknown" outside git).
TEST_F(GranjetCommand, VersionNamesTheCommit) {
  ASSERT_EQ(granjet("--version"), 0);
  std::ifstream in(dir_ / "stdout.txt");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind(std::string("granjet ") + GRANJET_VERSION + " (commit ", 0), 0u) << line;
  EXPECT_GT(line.size(), std::string("granjet  (commit )").size() + 6) << line;
}

// A step coarser than 0.05 t_c runs, but says what it costs (no blow-up would tell).
TEST_F(GranjetCommand, CoarseStepRunsWithANoteNamingItsCost) {
  const fs::path out = dir_ / "coarse.h5";
  EXPECT_EQ(
      granjet("run " + scene("binary.ini") + " --quiet --set run.dt=0.01 --out " + out.string()), 0)
      << err_;
  EXPECT_NE(err_.find("run.dt = 0.1 t_c"), std::string::npos) << err_;
  EXPECT_EQ(granjet("run " + scene("binary.ini") + " --quiet --out " + out.string()), 0);
  EXPECT_EQ(err_.find("run.dt"), std::string::npos) << err_;  // the study's 0.02 t_c: silent
}

TEST_F(GranjetCommand, BlowUpStopsWithStepAndGrainsAndKeepsAReadablePartialFile) {
  // dt = 0.9 t_c is far beyond the spring's stability limit: the first impacts explode.
  const fs::path out = dir_ / "blow.h5";
  EXPECT_EQ(granjet("run " + scene("jet3d.ini") +
                    " --quiet --set jet.grains=300 --set run.t_end=20 --set run.dt=0.09"
                    " --set output.interval=0.9 --out " +
                    out.string()),
            3);
  EXPECT_NE(err_.find("blow-up at step"), std::string::npos) << err_;
  EXPECT_NE(err_.find("grains"), std::string::npos) << err_;
  EXPECT_FALSE(fs::exists(out));
  const fs::path partial = out.string() + ".partial";
  ASSERT_TRUE(fs::exists(partial));
  const auto summary = analysis::read_summary(partial);
  EXPECT_NE(summary.status.find("blow-up"), std::string::npos);
  EXPECT_GE(summary.frames, 1u);
}

// CLI habits: every subcommand answers --help, the progress rows carry the step and
// the energies, the output is named at start and end, and the H5MD author is the user's.
TEST_F(GranjetCommand, SubcommandHelpProgressColumnsAndAuthor) {
  for (const std::string command : {"run", "resume", "compare", "campaign", "info", "analyze"}) {
    ASSERT_EQ(granjet(command + " --help"), 0) << command << ": " << err_;
    std::ifstream in(dir_ / "stdout.txt");
    const std::string help{std::istreambuf_iterator<char>(in), {}};
    EXPECT_NE(help.find("granjet " + command + " "), std::string::npos) << help;
    EXPECT_NE(help.find(command + " options"), std::string::npos) << help;
  }
  const fs::path out = dir_ / "a.h5";
  ASSERT_EQ(granjet("run " + scene("jet3d.ini") + " --set jet.grains=200 --set run.t_end=2" +
                    " --set run.progress_interval=1 --author 'A. Physicist' --out " + out.string()),
            0)
      << err_;
  std::ifstream in(dir_ / "stdout.txt");
  const std::string printed{std::istreambuf_iterator<char>(in), {}};
  const std::vector<std::string> words = {"writing " + out.string(), "step", "E_kin", "E_diss",
                                          "wrote " + out.string()};
  for (const std::string& word : words)
    EXPECT_NE(printed.find(word), std::string::npos) << word << " in\n" << printed;
  const std::string h5dump =
      "h5dump -a /h5md/author/name " + out.string() + " > " + (dir_ / "author.txt").string();
  ASSERT_EQ(std::system(h5dump.c_str()), 0);
  std::ifstream author(dir_ / "author.txt");
  EXPECT_NE(std::string(std::istreambuf_iterator<char>(author), {}).find("A. Physicist"),
            std::string::npos);
}

// As LAMMPS's log.lammps: the run's folder keeps the command, the resolved scene, the rows the
// terminal showed (also with --quiet) and the summary; a resume appends; --no-log writes none.
TEST_F(GranjetCommand, RunLogKeepsSceneRowsAndSummary) {
  const fs::path out = dir_ / "logged.h5";
  ASSERT_EQ(granjet("run " + scene("binary.ini") + " --quiet --set run.progress_interval=0.1" +
                    " --out " + out.string()),
            0)
      << err_;
  std::ifstream in(dir_ / "logged.log");
  const std::string log{std::istreambuf_iterator<char>(in), {}};
  for (const std::string& part :
       {std::string("# granjet "), std::string("binary.ini --backend soft_dem"),
        std::string("# resolved scene\n[scene]\nname = binary"), std::string("E_diss"),
        std::string("   0.500  100.0%"), std::string("measured contact_time"),
        std::string("# summary\n{"), std::string("\"status\": \"complete\""),
        "wrote " + out.string()})
    EXPECT_NE(log.find(part), std::string::npos) << part << " in\n" << log;
  const fs::path quiet = dir_ / "unlogged.h5";
  ASSERT_EQ(granjet("run " + scene("binary.ini") + " --quiet --no-log --out " + quiet.string()), 0);
  EXPECT_FALSE(fs::exists(dir_ / "unlogged.log"));
  // The log is one of the run's outputs: it may not be the summary.
  EXPECT_EQ(granjet("run " + scene("binary.ini") + " --out " + out.string() + " --summary " +
                    (dir_ / "logged.log").string()),
            2);
}

}  // namespace
}  // namespace granjet
