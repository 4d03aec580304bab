// A run's measurements read back from its file are the ones it stored, bit for bit: what lets
// separate processes (run --seeds, campaigns) combine their seeds from the run files.
#include "analysis/field_reader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>

#include "analysis/field_writer.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

// One 3D run of random grains over the study's rings, with a few bonds.
RunResult measured_run(std::uint64_t seed) {
  Scene scene;
  scene.contact.friction = 0.2;
  AnalysisConfig c = AnalysisConfig::for_scene(scene);
  c.window_start = 1.0;
  c.window_end = 3.0;
  c.sample_interval = 0.5;
  RunAnalysis<3> run(c);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double t = 0.0; t <= 3.0; t += 0.5) {
    Particles<3> p;
    for (int i = 0; i < 300; ++i)
      p.add(i, GrainKind::kFree, {10.0 * u(rng), 10.0 * u(rng), 3.0 + 2.5 * u(rng)},
            {u(rng), u(rng), u(rng) - 1.0}, 0.5, 1.0);
    const std::vector<PairImpulse<3>> bonds{
        {0, 1, {1.0, 0.5, 2.0}, {1.5, 0.5, 2.5}, {0.1 * u(rng), 0.0, -0.3}}};
    run.sample(t, p, bonds);
  }
  return run.finish();
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_table(const Table& read, const Table& stored, const char* what) {
  ASSERT_EQ(read.rows(), stored.rows()) << what;
  ASSERT_EQ(read.names().size(), stored.names().size()) << what;
  for (const std::string& name : stored.names()) {
    ASSERT_TRUE(read.has(name)) << what << " " << name;
    for (std::size_t row = 0; row < stored.rows(); ++row)
      EXPECT_TRUE(same_bits(read.at(row, name), stored.at(row, name)))
          << what << " " << name << " row " << row << ": " << read.at(row, name) << " vs "
          << stored.at(row, name);
  }
}

class FieldReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("granjet_field_reader_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(FieldReader, ReadsBackEveryStoredValueBitForBit) {
  const RunResult stored = measured_run(7);
  const fs::path file = dir_ / "run.h5";
  write_ensemble(file, std::vector<RunResult>{stored}, 3);
  ASSERT_TRUE(has_analysis(file));
  const RunResult read = read_run_result(file);
  EXPECT_EQ(read.edges.lateral, stored.edges.lateral);
  EXPECT_EQ(read.edges.height, stored.edges.height);
  expect_same_table(read.layout, stored.layout, "layout");
  expect_same_table(read.fields, stored.fields, "fields");
  expect_same_table(read.global, stored.global, "global");
  expect_same_table(read.vdf, stored.vdf, "vdf");
  expect_same_table(read.azimuth, stored.azimuth, "azimuth");
}

TEST_F(FieldReader, EnsemblesFromFilesEqualEnsemblesFromMemory) {
  const std::vector<RunResult> memory{measured_run(1), measured_run(2), measured_run(3)};
  std::vector<RunResult> files;
  for (std::size_t k = 0; k < memory.size(); ++k) {
    const fs::path f = dir_ / ("seed" + std::to_string(k) + ".h5");
    write_ensemble(f, std::vector<RunResult>{memory[k]}, 3);
    files.push_back(read_run_result(f));
  }
  const EnsembleResult a = combine_runs(memory, 3), b = combine_runs(files, 3);
  for (const std::string& name : a.fields.names())
    for (std::size_t row = 0; row < a.fields.rows(); ++row) {
      EXPECT_TRUE(same_bits(a.fields.at(row, name).mean, b.fields.at(row, name).mean)) << name;
      EXPECT_TRUE(same_bits(a.fields.at(row, name).std, b.fields.at(row, name).std)) << name;
    }
  ASSERT_EQ(a.fits.size(), b.fits.size());
  for (std::size_t k = 0; k < a.fits.size(); ++k)
    for (Eigen::Index p = 0; p < a.fits[k].value.size(); ++p)
      EXPECT_TRUE(same_bits(a.fits[k].value[p], b.fits[k].value[p])) << a.fits[k].law;
}

TEST_F(FieldReader, RefusesEnsemblesAndFilesWithoutAnalysis) {
  const fs::path ensemble = dir_ / "ensemble.h5";
  write_ensemble(ensemble, std::vector<RunResult>{measured_run(1), measured_run(2)}, 3);
  EXPECT_THROW(read_run_result(ensemble), std::runtime_error);
  EXPECT_FALSE(has_analysis(dir_ / "missing.h5"));
  EXPECT_THROW(read_run_result(dir_ / "missing.h5"), std::runtime_error);
}

}  // namespace
}  // namespace granjet::analysis
