// The analysis through the command: inline during `run` (fields in the summary and the file)
// and afterwards with `analyze` on stored frames, which must agree on the kinetic fields when
// they sample the same times.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "analysis/field_reader.hpp"
#include "analysis/h5md_reader.hpp"

namespace granjet {
namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

int run(const std::string& args) {
  return WEXITSTATUS(
      std::system((std::string(GRANJET_BINARY) + " " + args + " > /dev/null").c_str()));
}

TEST(AnalysisCommand, InlineFieldsAndStoredFrameAnalysisAgreeOnKineticFields) {
  const fs::path dir = fs::temp_directory_path() / "granjet_analysis_command";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path h5 = dir / "jet.h5";
  ASSERT_EQ(run("run " + std::string(GRANJET_SCENES_DIR) + "/jet3d.ini --quiet" +
                " --set jet.grains=3000 --set run.t_end=8 --set output.interval=0.5" +
                " --set analysis.window_start=4 --set analysis.window_end=8" +
                " --set analysis.sample_interval=0.5 --out " + h5.string() + " --summary " +
                (dir / "run.json").string()),
            0);
  const nlohmann::json inline_fields = read_json(dir / "run.json")["analysis"];
  ASSERT_EQ(inline_fields["bins"].size(), 5u);  // the 3D rings
  EXPECT_TRUE(fs::exists(dir / "jet.fields.xmf"));
  const std::vector<double> stored_p = analysis::read_analysis_values(h5, "/fields/P/mean");
  ASSERT_EQ(stored_p.size(), 5u);
  EXPECT_GT(stored_p[0], 0.0);  // the jet presses on the target: positive pressure at the axis
  EXPECT_DOUBLE_EQ(stored_p[0], inline_fields["bins"][0]["P"]["mean"].get<double>());

  ASSERT_EQ(run("analyze " + h5.string() + " --summary " + (dir / "frames.json").string()), 0);
  const nlohmann::json frames = read_json(dir / "frames.json");
  for (std::size_t bin = 0; bin < 5; ++bin) {
    SCOPED_TRACE(bin);
    for (const char* field : {"n", "phi", "T_g"}) {
      const double a = inline_fields["bins"][bin][field]["mean"].get<double>();
      const double b = frames["bins"][bin][field]["mean"].get<double>();
      EXPECT_NEAR(a, b, 1e-12 * std::abs(a)) << field;
    }
    EXPECT_TRUE(frames["bins"][bin]["stress_contact"]["rz"]["mean"].is_null());  // none stored
  }
  // A second analysis replaces the first without keeping its space.
  const std::uintmax_t analysed_once = fs::file_size(h5);
  ASSERT_EQ(run("analyze " + h5.string()), 0);
  EXPECT_EQ(fs::file_size(h5), analysed_once);
  EXPECT_EQ(run("analyze " + h5.string() + " --window 9:10"), 2);  // no frame in the window
  fs::remove_all(dir);
}

TEST(AnalysisCommand, SeedsMakeAnEnsembleWithItsSpread) {
  const fs::path dir = fs::temp_directory_path() / "granjet_analysis_seeds";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string base = "run " + std::string(GRANJET_SCENES_DIR) + "/jet3d.ini --quiet" +
                           " --set jet.grains=1500 --set run.t_end=5 --set output.interval=0" +
                           " --set analysis.window_start=3 --set analysis.window_end=5";
  // Another run's file under the ensemble's name is replaced, not merged into.
  ASSERT_EQ(run(base + " --set run.seed=9 --out " + (dir / "e.h5").string()), 0);
  ASSERT_EQ(run(base + " --seeds 1,2 --out " + (dir / "e.h5").string() + " --summary " +
                (dir / "e.json").string()),
            0);
  const analysis::FileSummary stored = analysis::read_summary(dir / "e.h5");
  EXPECT_EQ(stored.frames, 0u);
  EXPECT_EQ(stored.status, "complete");
  EXPECT_EQ(stored.members, (std::vector<std::string>{"e.seed1.h5", "e.seed2.h5"}));
  EXPECT_FALSE(fs::exists(dir / "e.h5.partial"));
  EXPECT_FALSE(fs::exists(dir / "e.xmf"));  // the other run's frames sidecar went with them
  EXPECT_EQ(run("info " + (dir / "e.h5").string()), 0);
  // analyze re-analyses the members' frames in a new window and combines them again.
  ASSERT_EQ(run("analyze " + (dir / "e.h5").string() + " --window 4:5 --summary " +
                (dir / "re.json").string()),
            0);
  EXPECT_EQ(read_json(dir / "re.json")["seeds"], 2);
  EXPECT_TRUE(fs::exists(dir / "e.seed1.h5"));
  EXPECT_TRUE(fs::exists(dir / "e.seed2.json"));
  const nlohmann::json e = read_json(dir / "e.json");
  EXPECT_EQ(e["analysis"]["seeds"], 2);
  const nlohmann::json t_g = e["analysis"]["bins"][0]["T_g"];
  EXPECT_EQ(t_g["count"], 2);
  EXPECT_GT(t_g["std"].get<double>(), 0.0);  // two random site removals differ
  // The ensemble mean is the mean of the two runs.
  const double one = read_json(dir / "e.seed1.json")["analysis"]["bins"][0]["T_g"]["mean"];
  const double two = read_json(dir / "e.seed2.json")["analysis"]["bins"][0]["T_g"]["mean"];
  EXPECT_NEAR(t_g["mean"].get<double>(), 0.5 * (one + two), 1e-12 * std::abs(one));
  EXPECT_EQ(analysis::read_analysis_values(dir / "e.h5", "/fields/T_g/mean").size(), 5u);
  EXPECT_EQ(run(base + " --seeds 3..1"), 2);
  EXPECT_EQ(run(base + " --seeds x"), 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granjet
