// Stability (b): figure FE.1 of the study [model §7]: with mu_p = 1.0 the 2D jet's granular
// temperature in layer (a), -dy < y < 0, flows in bursts when the grains are soft (long t_c)
// and the bursts die away as the grains get stiffer (the study's mu_p = 1.0 runs use
// t_c = 0.01 for that reason). Soft DEM backend, AB2, e = 0.75 [3.4]-[3.5], t_c = 0.1, 0.05
// and 0.01.
//
// Measured on a jet smaller than the study's (strip 20 d, 2000 grains, three seeds, window
// 30 <= t <= 100; the stiff run costs 1/t_c steps per unit time), or at the study's size with
// GRANJET_STABILITY_FE1_FULL=1 in the environment (strip 30 d, 8000 grains, window
// 180 <= t <= 300, the model's ensemble of 10 seeds: about 17 minutes on one core, three
// quarters of it t_c = 0.01). T_g(t) is sampled every 0.25:
// T_g = sum m |v - <v>|^2 / (2 N) over the grains whose centres lie in layer (a)
// (0 < x - wall surface <= 5 d) and -dy < y < 0 (dy = R_tar/5, as in model §6).
//
// FE.1 is a figure of T_g(t) (scripts/plot_fe1.py draws ours from the `fe1.tcX.seedN.series`
// lines). What it shows, measured per seed on T_g(t) itself:
// - std: the standard deviation of the samples, how far T_g swings;
// - peak: the largest sample, the height of the highest burst.
// Expected (FE.1), asserted: both fall from soft (t_c = 0.1) to stiff (t_c = 0.01) grains, by
// more than twice the standard error of the difference of their means over the seeds.
// Reported, not asserted: the same swings relative to the mean level, CV = std/mean,
// max/median, and the block CV (the CV of 2 d/u0 block means: a burst is a collective flow
// lasting many contact times, while the 25-45 grains of the bin add noise to every sample).
// They do not fall with t_c: the soft grains are hotter and burst higher, in proportion to
// their level (docs/stability.md, case b).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <utility>
#include <vector>

#include "analysis/layer_temperature.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "stability_common.hpp"

namespace granjet::stability {
namespace {

struct BurstMeasure {
  double mean = 0.0;
  double cv = 0.0;  // std / mean of T_g(t)
  double max_over_median = 0.0;
  double block_cv = 0.0;     // of 2 d/u0 block means
  double std = 0.0;          // of T_g(t)
  double peak = 0.0;         // the largest T_g(t)
  double mean_grains = 0.0;  // grains in the bin, averaged over the samples
  double seconds = 0.0;
  std::vector<double> series;
};

constexpr double kSample = 0.25;
constexpr int kBlock = 8;  // samples per block: 2 d/u0

bool study_size() { return std::getenv("GRANJET_STABILITY_FE1_FULL") != nullptr; }
double window_start() { return study_size() ? 180.0 : 30.0; }

double average(const std::vector<double>& x) {
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

// Sample standard deviation (n - 1).
double standard_deviation(const std::vector<double>& x) {
  const double mean = average(x);
  double var = 0.0;
  for (double v : x) var += (v - mean) * (v - mean);
  return std::sqrt(var / (static_cast<double>(x.size()) - 1.0));
}

double coefficient_of_variation(const std::vector<double>& x) {
  return standard_deviation(x) / average(x);
}

BurstMeasure measure_bursts(double contact_time, int seed) {
  std::vector<std::string> overrides{"contact.friction=1.0",
                                     "contact.contact_time=" + std::to_string(contact_time),
                                     "run.seed=" + std::to_string(seed), "analysis.enabled=false",
                                     // heights from the target grains' top surface
                                     "analysis.height_origin=wall_surface"};
  const bool full = study_size();
  if (!full)
    for (const char* o : {"jet.diameter=20", "wall.diameter=44", "jet.grains=2000",
                          "region.radius=88", "run.t_end=100"})
      overrides.push_back(o);
  const Scene scene = shipped_scene("jet2d", overrides);
  const double window_end = scene.run.t_end;
  Stopwatch clock;
  auto sim = dem::make_dem_simulator<2>(scene);
  BurstMeasure m;
  double grains = 0.0;
  for (double t = window_start(); t <= window_end + 1e-9; t += kSample) {
    sim->advance_to(t);
    int count = 0;
    const double tg = analysis::layer_a_temperature(sim->particles(), scene, &count);
    grains += count;
    m.series.push_back(std::isnan(tg) ? 0.0 : tg);
  }
  m.seconds = clock.seconds();
  m.mean_grains = grains / static_cast<double>(m.series.size());
  m.mean = average(m.series);
  m.std = standard_deviation(m.series);
  m.cv = m.std / m.mean;
  std::vector<double> blocks;
  for (std::size_t k = 0; k + kBlock <= m.series.size(); k += kBlock)
    blocks.push_back(std::accumulate(m.series.begin() + k, m.series.begin() + k + kBlock, 0.0) /
                     kBlock);
  m.block_cv = coefficient_of_variation(blocks);
  std::vector<double> sorted = m.series;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  m.peak = sorted.back();
  m.max_over_median = m.peak / median;
  return m;
}

std::vector<double> over_seeds(const std::vector<BurstMeasure>& runs, double BurstMeasure::*field) {
  std::vector<double> x;
  for (const BurstMeasure& m : runs) x.push_back(m.*field);
  return x;
}

// "mean +- std" over the seeds of one measure.
std::string spread(const std::vector<BurstMeasure>& runs, double BurstMeasure::*field) {
  const std::vector<double> x = over_seeds(runs, field);
  return x.size() < 2 ? cat(x[0]) : cat(average(x), " +- ", standard_deviation(x));
}

TEST(Fe1Bursts, FE1_LayerATemperatureBurstsForSoftGrainsAndCalmsForStiffOnes) {
  const int seed_count = study_size() ? 10 : 3;
  std::vector<std::vector<BurstMeasure>> runs;  // per t_c, per seed
  for (double tc : {0.1, 0.05, 0.01}) {
    std::vector<BurstMeasure>& at_tc = runs.emplace_back();
    for (int seed = 1; seed <= seed_count; ++seed) {
      const BurstMeasure& m = at_tc.emplace_back(measure_bursts(tc, seed));
      report(cat("fe1.tc", tc, ".seed", seed),
             cat("<T_g> = ", m.mean, ", CV = ", m.cv, ", max/median = ", m.max_over_median,
                 ", block CV = ", m.block_cv, ", std = ", m.std, ", peak = ", m.peak,
                 ", grains in bin ", m.mean_grains, ", ", m.seconds, " s"));
      std::string series = cat("from ", window_start(), " every ", kSample, ":");
      for (double x : m.series) series += cat(" ", x);
      report(cat("fe1.tc", tc, ".seed", seed, ".series"), series);
    }
    report(cat("fe1.tc", tc),
           cat(study_size() ? "study size" : "2000 grains", ", mean +- std over seeds 1-",
               seed_count, ": <T_g> = ", spread(at_tc, &BurstMeasure::mean),
               ", CV = ", spread(at_tc, &BurstMeasure::cv),
               ", max/median = ", spread(at_tc, &BurstMeasure::max_over_median),
               ", block CV = ", spread(at_tc, &BurstMeasure::block_cv), ", std = ",
               spread(at_tc, &BurstMeasure::std), ", peak = ", spread(at_tc, &BurstMeasure::peak)));
  }
  const std::vector<BurstMeasure>& soft = runs.front();
  const std::vector<BurstMeasure>& stiff = runs.back();
  for (auto [name, field] :
       {std::pair{"std", &BurstMeasure::std}, std::pair{"peak", &BurstMeasure::peak}}) {
    const std::vector<double> at_soft = over_seeds(soft, field);
    const std::vector<double> at_stiff = over_seeds(stiff, field);
    const double drop = average(at_soft) - average(at_stiff);
    const double error = std::hypot(standard_deviation(at_soft) / std::sqrt(at_soft.size()),
                                    standard_deviation(at_stiff) / std::sqrt(at_stiff.size()));
    report(cat("fe1.", name, "_drop_soft_to_stiff"),
           cat(drop, " (", drop / error, " standard errors)"));
    EXPECT_GT(drop, 2.0 * error) << "FE.1: the " << name
                                 << " of T_g(t) should fall from soft to stiff grains";
  }
}

}  // namespace
}  // namespace granjet::stability
