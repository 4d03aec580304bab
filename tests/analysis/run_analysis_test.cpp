// One run's sampling (window, transfer times), the ensemble statistics over seeds, and the JSON
// and HDF5 output of the result.
#include "analysis/run_analysis.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <vector>

#include "analysis/analysis_json.hpp"
#include "analysis/field_reader.hpp"
#include "analysis/field_writer.hpp"
#include "analysis/h5md_reader.hpp"
#include "analysis/h5md_writer.hpp"
#include "core/plate_face.hpp"

namespace granjet::analysis {
namespace {

namespace fs = std::filesystem;

Scene jet_scene(int dimension, double target_diameter, double friction) {
  Scene s;
  s.dimension = dimension;
  s.wall.diameter = target_diameter;
  s.contact.friction = friction;
  if (dimension == 2) s.analysis = {true, 180.0, 300.0, 0.5, 10, 2, 5.0};  // as scenes/jet2d.ini
  return s;
}

// Heights from the target grains' top surface: grains() fills bin 5 of layer (a) with the grains
// at 4.5 < h <= 5 that this origin gives it.
AnalysisConfig small_2d_config() {
  Scene s = jet_scene(2, 66.0, 0.0);
  s.analysis.height_origin = HeightOrigin::kWallSurface;
  AnalysisConfig c = AnalysisConfig::for_scene(s);
  c.window_start = 1.0;
  c.window_end = 2.0;
  c.sample_interval = 0.5;
  return c;
}

// Grains in a few bins with seeded random velocities, and one bond inside bin 5 of layer (a).
Particles<2> grains(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 0.2);
  Particles<2> p;
  for (int i = 0; i < 400; ++i)
    p.add(i, GrainKind::kFree, {1.0 + 0.02 * i, -30.0 + 0.15 * i}, {g(rng) - 1.0, g(rng)}, 0.5,
          1.0);
  return p;
}

const std::vector<PairImpulse<2>> kBond{{0, 1, {3.0, 1.0}, {3.0, 2.0}, {0.0, -0.5}}};

// The bin (-1: none) that the scene's mesh puts a grain centre at x in.
template <int D>
int bin_of(const Scene& scene, const Vec<D>& x) {
  const BinCoordinates<D> coords(AnalysisConfig::for_scene(scene).bins);
  return coords.grid().bin_at(coords.lateral(x), coords.height(x));
}

Scene with_origin(Scene s, HeightOrigin origin) {
  s.analysis.height_origin = origin;
  return s;
}

// Spec §6 "Height origin": the layers start at the target grains' centre plane (wall_centres,
// the default: z = 0 in 3D, x = 0 in 2D) or at their top surface d/2 above it (wall_surface).
TEST(HeightOrigin, Spec6_GrainLandsInTheLayerOfItsHeightUnderEachOrigin) {
  constexpr auto kCentres = HeightOrigin::kWallCentres;
  constexpr auto kSurface = HeightOrigin::kWallSurface;
  EXPECT_EQ(Scene{}.analysis.height_origin, kCentres);
  EXPECT_EQ(AnalysisConfig::for_scene(Scene{}).bins.height_origin, 0.0);
  // 2D, layers (a) 0 < h <= 5 and (b) 5 < h <= 10; y = 1 is in lateral bin 5 of 10.
  const Scene s2 = jet_scene(2, 66.0, 0.0);
  EXPECT_EQ(bin_of<2>(with_origin(s2, kCentres), {5.3, 1.0}), 15);   // h = 5.3: layer (b)
  EXPECT_EQ(bin_of<2>(with_origin(s2, kSurface), {5.3, 1.0}), 5);    // h = 4.8: layer (a)
  EXPECT_EQ(bin_of<2>(with_origin(s2, kCentres), {0.3, 1.0}), 5);    // h = 0.3: layer (a)
  EXPECT_EQ(bin_of<2>(with_origin(s2, kSurface), {0.3, 1.0}), -1);   // below the surface
  EXPECT_EQ(bin_of<2>(with_origin(s2, kSurface), {10.3, 1.0}), 15);  // h = 9.8: layer (b)
  EXPECT_EQ(bin_of<2>(with_origin(s2, kCentres), {10.3, 1.0}), -1);  // above the mesh
  // 3D, one layer 0 < h <= 5; r = 1 is in the inner ring.
  const Scene s3 = jet_scene(3, 22.0, 0.2);
  EXPECT_EQ(bin_of<3>(with_origin(s3, kCentres), {0.6, 0.8, 5.2}), -1);  // h = 5.2: above
  EXPECT_EQ(bin_of<3>(with_origin(s3, kSurface), {0.6, 0.8, 5.2}), 0);   // h = 4.7
  EXPECT_EQ(bin_of<3>(with_origin(s3, kCentres), {0.6, 0.8, 0.4}), 0);   // h = 0.4
  EXPECT_EQ(bin_of<3>(with_origin(s3, kSurface), {0.6, 0.8, 0.4}), -1);  // h = -0.1: below
}

// With a plate target the surface origin is the plate's face (core/plate_face.hpp), and the
// centre origin the plane d/2 behind it, where target grains would have their centres.
TEST(HeightOrigin, Spec6_SurfaceOriginOfAPlateIsItsFace) {
  Scene s = jet_scene(3, 22.0, 0.2);
  s.wall.kind = WallKind::kPlate;
  const PlateFace<3> plate(s.wall.diameter);
  const Vec<3> x(1.0, 2.0, 3.7);
  const auto rings = [&](HeightOrigin origin) {
    return CylindricalRings(AnalysisConfig::for_scene(with_origin(s, origin)).bins);
  };
  const CylindricalRings surface = rings(HeightOrigin::kWallSurface);
  const CylindricalRings centres = rings(HeightOrigin::kWallCentres);
  EXPECT_DOUBLE_EQ(surface.height(x), plate.height(x));
  EXPECT_DOUBLE_EQ(centres.height(x), plate.height(x) + 0.5);
}

// F4.3's v2 (model §6): phi is measured from the short side of a rectangular jet (long side along
// x), so phi = 0 is e_x. Scattered grains evenly spaced in t on an ellipse (A cos t, B sin t)
// outside the scatter radius have <cos 2 phi> = (1 - k)/(1 + k), k = B/A: +0.25 for k = 0.6
// (elongated along x, towards the short sides), -0.25 when elongated along y.
TEST(Anisotropy, F4_3_V2SignFollowsTheElongationFromTheShortSide) {
  Scene s = jet_scene(3, 22.0, 0.2);
  s.jet.shape = JetShape::kRectangle;
  s.jet.aspect_ratio = 4.0;
  const AnalysisConfig c = AnalysisConfig::for_scene(s);
  EXPECT_EQ(c.reference_azimuth, 0.0);
  const double big = 2.0 * c.scatter_radius, small = 1.2 * c.scatter_radius;  // k = 0.6
  for (const bool along_x : {true, false}) {
    SCOPED_TRACE(along_x ? "elongated along x" : "elongated along y");
    ScatteringMeasurement<3> m(c.scatter_radius, c.reference_azimuth);
    Particles<3> p;
    for (int k = 0; k < 360; ++k) {
      const double t = 2.0 * std::numbers::pi * (k + 0.5) / 360;
      const double x = (along_x ? big : small) * std::cos(t);
      const double y = (along_x ? small : big) * std::sin(t);
      p.add(k, GrainKind::kFree, {x, y, 1.0}, {x, y, 0.0}, 0.5, 1.0);
    }
    m.observe(p, 0.0);
    ASSERT_EQ(m.count(), 360u);
    EXPECT_NEAR(m.v2(), along_x ? 0.25 : -0.25, 1e-12);
  }
}

TEST(RunAnalysis, SamplesEveryIntervalAndAveragesTransfersOverTheWindowOnly) {
  RunAnalysis<2> run(small_2d_config());
  const Particles<2> p = grains(1);
  std::vector<double> times;
  for (int k = 0; k < 8; ++k) {
    const double t = run.next_sample_time();
    times.push_back(t);
    ASSERT_TRUE(run.due(t));
    // Every sample brings the same bond: before and at the window's opening it is discarded.
    run.sample(t, p, kBond);
  }
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5}));
  const RunResult r = run.finish();
  EXPECT_EQ(r.global.at(0, "samples"), 3.0);        // t = 1, 1.5, 2
  EXPECT_EQ(r.global.at(0, "transfer_time"), 1.0);  // (1, 2]
  // Two bonds of J r^T = 0.5 over tau = 1 and the bin area 6.6 x 5.
  EXPECT_NEAR(r.fields.at(5, "stress_contact.yy"), 2 * 0.5 / (6.6 * 5.0), 1e-15);
}

// analysis.psi0 chooses the reading that global psi0 and psi0_window report; both readings are
// stored whatever it says. Beyond the scatter radius one grain leaves along the wall at u0 = 2,
// one straight back towards the source at u0/4.
TEST(RunAnalysis, Psi0ReportsTheChosenReadingAndStoresBoth) {
  Scene s = jet_scene(2, 66.0, 0.0);
  s.jet.speed = 2.0;
  for (const Psi0Reading reading : {Psi0Reading::kDeparture, Psi0Reading::kMomentum}) {
    s.analysis.psi0 = reading;
    AnalysisConfig c = AnalysisConfig::for_scene(s);
    c.window_start = 0.0;
    c.window_end = 1.0;
    RunAnalysis<2> run(c);
    Particles<2> p;
    p.add(0, GrainKind::kFree, {1.0, 2.0 * c.scatter_radius}, {0.0, 2.0}, 0.5, 1.0);
    p.add(1, GrainKind::kFree, {1.0, -2.0 * c.scatter_radius}, {0.5, 0.0}, 0.5, 1.0);
    run.sample(0.5, p, {});
    const Table g = run.finish().global;
    // Unit vectors (along wall, forward): (1, 0) and (0, -1); mean (0.5, -0.5).
    EXPECT_NEAR(g.at(0, "psi0_departure"), std::atan2(0.5, -0.5), 1e-12);
    // Forward momentum 0 + (-0.5) over 2 grains x u0 = 2: cos psi0 = -0.125.
    EXPECT_NEAR(g.at(0, "psi0_momentum"), std::acos(-0.125), 1e-12);
    const char* chosen = reading == Psi0Reading::kMomentum ? "psi0_momentum" : "psi0_departure";
    EXPECT_EQ(g.at(0, "psi0"), g.at(0, chosen));
    EXPECT_EQ(g.at(0, "psi0_window"), g.at(0, chosen));
    EXPECT_EQ(g.at(0, "psi0_departure_window"), g.at(0, "psi0_departure"));  // seen in window
    EXPECT_EQ(g.at(0, "psi0_momentum_window"), g.at(0, "psi0_momentum"));
  }
}

TEST(RunAnalysis, ScheduleStopsAtTheWindowStart) {
  AnalysisConfig c = small_2d_config();
  c.window_start = 0.7;
  RunAnalysis<2> run(c);
  run.sample(0.5, grains(1), {});
  EXPECT_DOUBLE_EQ(run.next_sample_time(), 0.7);
  run.sample(0.7, grains(1), {});
  EXPECT_DOUBLE_EQ(run.next_sample_time(), 1.0);
}

TEST(Ensemble, MeanStandardDeviationAndStandardErrorOverSeeds) {
  std::vector<Table> runs(3, Table(2));
  const double values[3] = {1.0, 2.0, 3.0};
  for (int s = 0; s < 3; ++s) {
    runs[s].set("x", 0, values[s]);
    runs[s].set("x", 1, s == 1 ? std::nan("") : values[s]);  // an empty bin in one seed
  }
  const EnsembleTable e(runs);
  EXPECT_DOUBLE_EQ(e.at(0, "x").mean, 2.0);
  EXPECT_DOUBLE_EQ(e.at(0, "x").std, 1.0);
  EXPECT_DOUBLE_EQ(e.at(0, "x").sem, 1.0 / std::sqrt(3.0));
  EXPECT_EQ(e.at(1, "x").count, 2);
  EXPECT_DOUBLE_EQ(e.at(1, "x").std, std::sqrt(2.0));
  runs[2].set("y", 0, 1.0);
  EXPECT_THROW(EnsembleTable{runs}, std::invalid_argument);
}

std::vector<RunResult> seeds_of_2d_runs() {
  std::vector<RunResult> runs;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    RunAnalysis<2> run(small_2d_config());
    for (double t = 1.0; t <= 2.0; t += 0.5) run.sample(t, grains(seed), kBond);
    runs.push_back(run.finish());
  }
  return runs;
}

TEST(Ensemble, JsonHasOneEntryPerBinWithSpreadsGlobalsAndFits) {
  const std::vector<RunResult> runs = seeds_of_2d_runs();
  const EnsembleResult e = combine_runs(runs, 2);
  const nlohmann::json j = to_json(e);
  ASSERT_EQ(j["bins"].size(), 20u);
  const auto& bin = j["bins"][5];
  EXPECT_EQ(bin["layer_name"], "a");
  EXPECT_EQ(j["bins"][15]["layer_name"], "b");
  EXPECT_NEAR(bin["y"].get<double>(), 3.3, 1e-12);
  EXPECT_NEAR(bin["h"].get<double>(), 2.5, 1e-12);
  for (const char* key : {"n", "phi", "T_g", "P", "D", "mu_star", "I_s", "I_T", "eta_star"}) {
    SCOPED_TRACE(key);
    ASSERT_TRUE(bin.contains(key));
    EXPECT_TRUE(bin[key].contains("mean") && bin[key].contains("std") && bin[key].contains("sem"));
  }
  for (const char* pair : {"xx", "xy", "yy"}) EXPECT_TRUE(bin["stress"].contains(pair));
  EXPECT_TRUE(bin["T_alpha"].contains("x"));
  EXPECT_EQ(bin["n"]["count"], 3);
  EXPECT_GT(bin["T_g"]["std"].get<double>(), 0.0);  // the seeds differ
  // T5.1 under both scalings (each bin's T_a, one T_a for the region); no unqualified global.
  for (const char* scaling : {"flatness_bin", "flatness_region"}) {
    SCOPED_TRACE(scaling);
    EXPECT_TRUE(j["global"][scaling].contains("x") && j["global"][scaling].contains("y"));
    EXPECT_TRUE(j["global"][scaling]["y"]["mean"].is_number());
  }
  EXPECT_FALSE(j["global"].contains("flatness"));
  EXPECT_EQ(j["vdf"]["c"].size(), 48u);
  for (const char* law : {"6.2", "6.3", "6.9", "6.10"}) EXPECT_TRUE(j["fits"].contains(law));
  EXPECT_FALSE(j.contains("azimuth"));  // 2D
}

TEST(Ensemble, ThreeDimensionalJsonNamesCylindricalComponents) {
  AnalysisConfig c = AnalysisConfig::for_scene(jet_scene(3, 22.0, 0.2));
  EXPECT_NEAR(c.options.restitution, 0.616, 5e-4);  // e-bar [2.55] for frictional grains
  EXPECT_EQ(c.window_start, 50.0);
  EXPECT_EQ(c.bins.target_radius, 11.0);
  RunAnalysis<3> run(c);
  Particles<3> p;
  for (int i = 0; i < 50; ++i)
    p.add(i, GrainKind::kFree, {0.2 * i, 0.1, 2.0}, {0.1 * (i % 3), 0.0, -0.5}, 0.5, 1.0);
  run.sample(50.0, p, {});
  run.sample(50.5, p, {});
  const RunResult r = run.finish();
  const nlohmann::json j = to_json(combine_runs(std::vector<RunResult>{r}, 3));
  EXPECT_NEAR(j["bins"][2]["r_over_R_tar"].get<double>(), 0.5, 1e-12);
  for (const char* pair : {"rr", "rz", "zz", "tt"})
    EXPECT_TRUE(j["bins"][0]["stress"].contains(pair));
  EXPECT_TRUE(j["bins"][0].contains("I"));
  EXPECT_TRUE(j["bins"][0].contains("sigma_Y"));
  EXPECT_TRUE(j["bins"][0]["stress_xyz"].contains("xz"));
  EXPECT_TRUE(j["fits"].contains("mu_linear"));
  EXPECT_EQ(j["azimuth"]["phi"].size(), 36u);
  EXPECT_TRUE(j["bins"][0]["n"]["std"].is_null());  // one seed: no spread
}

// /fields and /analysis go into an existing run file without disturbing it, and a second
// analysis replaces the first.
TEST(FieldWriter, WritesFieldsAndAnalysisIntoARunFile) {
  const fs::path dir =
      fs::temp_directory_path() / ("granjet_field_writer_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "run.h5";
  RunMetadata meta;
  meta.backend = "soft_dem";
  meta.dimension = 2;
  {
    H5mdWriter<2> writer(file, meta, 400);
    writer.write_frame(0, 0.0, grains(1));
    writer.finish();
  }
  const std::vector<RunResult> runs = seeds_of_2d_runs();
  const EnsembleResult e = combine_runs(runs, 2);
  write_analysis_hdf5(file, e);
  write_analysis_hdf5(file, e);
  write_fields_xdmf(dir / "run.fields.xmf", "run.h5", e);

  EXPECT_EQ(read_summary(file).frames, 1u);  // the run is still readable
  const std::vector<double> phi = read_analysis_values(file, "/fields/phi/mean");
  ASSERT_EQ(phi.size(), 20u);
  for (std::size_t k = 0; k < phi.size(); ++k)
    EXPECT_DOUBLE_EQ(phi[k], e.fields.at(k, "phi").mean) << k;
  EXPECT_EQ(read_analysis_values(file, "/fields/stress/xy/sem").size(), 20u);
  EXPECT_EQ(read_analysis_values(file, "/fields/mesh/lateral").size(), 11u);
  EXPECT_EQ(read_analysis_values(file, "/analysis/fits/6.9/value").size(), 3u);
  EXPECT_DOUBLE_EQ(read_analysis_values(file, "/analysis/global/samples/mean").at(0), 3.0);
  EXPECT_THROW(read_analysis_values(file, "/fields/nothing"), std::runtime_error);
  EXPECT_TRUE(fs::file_size(dir / "run.fields.xmf") > 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace granjet::analysis
