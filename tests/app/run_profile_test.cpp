// `granjet run --profile`: the loop's wall time by phase, and its serial share (Amdahl's bound
// on the speed-up), from core/phase_profile.hpp through run/run_profile.cpp to the summary.
#include "run/run_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "command_fixture.hpp"
#include "core/phase_profile.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;
using Kind = PhaseProfile::Kind;

TEST(PhaseProfile, DisabledTimersAddNothingAndEnabledOnesAddTheirScopesWallTime) {
  PhaseProfile profile;
  const int work = profile.phase("work", Kind::kParallel);
  EXPECT_EQ(profile.phase("work", Kind::kParallel), work);  // one phase per name
  { const PhaseProfile::Timer timing(&profile, work); }
  EXPECT_EQ(profile.phases()[work].calls, 0);
  profile.enable();
  {
    const PhaseProfile::Timer timing(&profile, work);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(profile.phases()[work].calls, 1);
  EXPECT_GE(profile.phases()[work].seconds, 0.020);
  EXPECT_LT(profile.phases()[work].seconds, 2.0);
}

TEST(PhaseProfile, SharesGiveTheThreadsMeanAndSlowestTimeAtWork) {
  PhaseProfile profile;
  const int loop = profile.phase("loop", Kind::kParallel);
  const std::vector<double> first = {0.1, 0.3}, second = {0.2, 0.2, 0.5};
  profile.add_shares(loop, first);  // disabled: nothing
  EXPECT_EQ(profile.phases()[loop].work_seconds, 0.0);
  profile.enable();
  profile.add_shares(loop, first);
  profile.add_shares(loop, second);
  { const PhaseProfile::Timer timing(&profile, loop); }  // a phase never run is left out
  EXPECT_NEAR(profile.phases()[loop].work_seconds, 0.2 + 0.3, 1e-15);
  EXPECT_NEAR(profile.phases()[loop].slowest_seconds, 0.3 + 0.5, 1e-15);
  const nlohmann::json j = profile_json(profile, 1.0, 3);
  ASSERT_EQ(j["phases"].size(), 1u);
  EXPECT_NEAR(j["phases"][0]["work_seconds"].get<double>(), 0.5, 1e-15);
  EXPECT_NEAR(j["phases"][0]["slowest_seconds"].get<double>(), 0.8, 1e-15);
}

TEST(RunProfile, SerialShareCountsSerialPhasesAndTheUntimedRest) {
  PhaseProfile profile;
  profile.enable();
  const int parallel = profile.phase("pairs", Kind::kParallel);
  const int serial = profile.phase("sweep", Kind::kSerial);
  profile.phase("never run", Kind::kSerial);
  {
    const PhaseProfile::Timer timing(&profile, parallel);
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  {
    const PhaseProfile::Timer timing(&profile, serial);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const double timed = profile.phases()[parallel].seconds + profile.phases()[serial].seconds;
  const double loop = timed + 0.010;  // 10 ms between the phases
  const nlohmann::json j = profile_json(profile, loop, 4);
  ASSERT_EQ(j["phases"].size(), 2u);  // the phase never run is left out
  EXPECT_EQ(j["phases"][0]["name"], "pairs");
  EXPECT_EQ(j["phases"][0]["kind"], "parallel");
  EXPECT_EQ(j["phases"][1]["kind"], "serial");
  EXPECT_FALSE(j["phases"][0].contains("work_seconds"));  // no shares reported
  EXPECT_NEAR(j["untimed_seconds"].get<double>(), 0.010, 1e-12);
  const double serial_seconds = profile.phases()[serial].seconds + 0.010;
  EXPECT_NEAR(j["serial_share"].get<double>(), serial_seconds / loop, 1e-12);
  EXPECT_NEAR(j["amdahl_limit"].get<double>(), loop / serial_seconds, 1e-9);
  const std::string text = profile_text(j);
  EXPECT_NE(text.find("pairs"), std::string::npos);
  EXPECT_NE(text.find("on 4 threads"), std::string::npos);
  EXPECT_NE(text.find("serial share"), std::string::npos);
}

// Over ranks: each phase's fastest rank, mean and slowest rank, a rank without a phase (the
// followers look at no output) counting zero, and the table that shows them.
TEST(RunProfile, OverRanksGivesEachPhasesSpread) {
  PhaseProfile profile;
  profile.enable();
  const int pass = profile.phase("pass", Kind::kParallel);
  const int output = profile.phase("output", Kind::kSerial);
  { const PhaseProfile::Timer timing(&profile, pass); }
  { const PhaseProfile::Timer timing(&profile, output); }
  const std::vector<std::vector<double>> by_rank = {{1.0, 0.5}, {3.0}, {2.0}};
  const nlohmann::json j = profile_json(profile, 4.0, 1, by_rank);
  EXPECT_EQ(j["ranks"], 3);
  const nlohmann::json& a = j["phases"][0]["over_ranks"];
  EXPECT_EQ(a["fastest"], 1.0);
  EXPECT_EQ(a["mean"], 2.0);
  EXPECT_EQ(a["slowest"], 3.0);
  const nlohmann::json& b = j["phases"][1]["over_ranks"];
  EXPECT_EQ(b["fastest"], 0.0);
  EXPECT_NEAR(b["mean"].get<double>(), 0.5 / 3.0, 1e-15);
  EXPECT_EQ(b["slowest"], 0.5);
  EXPECT_NE(profile_text(j).find("over 3 ranks"), std::string::npos);
  // One rank: no spread.
  const nlohmann::json alone = profile_json(profile, 4.0, 1, {{1.0, 0.5}});
  EXPECT_FALSE(alone.contains("ranks"));
  EXPECT_FALSE(alone["phases"][0].contains("over_ranks"));
  EXPECT_EQ(profile_text(alone).find("ranks"), std::string::npos);
}

using GranjetCommand = testing::CommandTest;

// The soft DEM's phases and the observers' looks are all there, their sum is within the loop's
// wall time, and profiling changes no result.
TEST_F(GranjetCommand, ProfileSplitsTheLoopByPhaseAndChangesNoResult) {
  const std::string args = "run " + scene("jet3d.ini") +
                           " --quiet --set jet.grains=400 --set run.t_end=4"
                           " --set output.interval=2 --set run.threads=2";
  const fs::path plain = dir_ / "plain.json", profiled = dir_ / "profiled.json";
  ASSERT_EQ(granjet(args + " --out " + (dir_ / "a.h5").string() + " --summary " + plain.string()),
            0)
      << err_;
  ASSERT_EQ(granjet(args + " --profile --out " + (dir_ / "b.h5").string() + " --summary " +
                    profiled.string()),
            0)
      << err_;
  std::ifstream printed(dir_ / "stdout.txt");
  const std::string table((std::istreambuf_iterator<char>(printed)), {});
  EXPECT_NE(table.find("serial share"), std::string::npos) << table;  // shown even with --quiet
  const nlohmann::json a = summary("plain.json"), b = summary("profiled.json");
  EXPECT_FALSE(a.contains("profile"));
  ASSERT_TRUE(b.contains("profile"));
  EXPECT_EQ(a["energy"], b["energy"]);  // bit for bit
  const nlohmann::json& p = b["profile"];
  EXPECT_EQ(p["threads"], 2);
  double timed = 0.0;
  std::vector<std::string> names;
  for (const nlohmann::json& phase : p["phases"]) {
    EXPECT_GE(phase["seconds"].get<double>(), 0.0);
    EXPECT_GT(phase["calls"].get<std::int64_t>(), 0);
    timed += phase["seconds"].get<double>();
    names.push_back(phase["name"]);
    if (phase.contains("work_seconds")) {  // the shares run inside the phase's wall time
      EXPECT_LE(phase["work_seconds"].get<double>(), phase["slowest_seconds"].get<double>());
      EXPECT_LE(phase["slowest_seconds"].get<double>(), phase["seconds"].get<double>());
    }
  }
  for (const char* expected :
       {"rebuild: pair list", "contacts: forces and sums", "grains: update", "observer: frames"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  for (const nlohmann::json& phase : p["phases"]) {
    if (phase["name"] == "contacts: forces and sums") {
      EXPECT_GT(phase["work_seconds"], 0.0);
    }
    // The step's phases are timed once a step (the tether hook included: jet3d is tethered).
    for (const char* per_step : {"tethered target", "contacts: distance test, history carry-over",
                                 "contacts: forces and sums", "grains: update"})
      if (phase["name"] == per_step) {
        EXPECT_EQ(phase["calls"], b["steps"]) << per_step;
      }
  }
  EXPECT_NE(table.find("busy"), std::string::npos) << table;
  EXPECT_LE(timed, p["loop_seconds"].get<double>() * (1.0 + 1e-9));
  EXPECT_GT(p["serial_share"].get<double>(), 0.0);
  EXPECT_LE(p["serial_share"].get<double>(), 1.0);
}

}  // namespace
}  // namespace granjet
