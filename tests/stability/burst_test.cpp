// Stability (b): figure FE.1 of the study [spec §7]: with mu_p = 1.0 the 2D jet's granular
// temperature in layer (a), -dy < y < 0, flows in bursts when the grains are soft (long t_c)
// and the bursts die away as the grains get stiffer (the study's mu_p = 1.0 runs use
// t_c = 0.01 for that reason). Soft DEM backend, AB2, e = 0.75 [3.4]-[3.5], t_c = 0.1, 0.05
// and 0.01.
//
// Measured on a jet smaller than the study's (strip 20 d, 2000 grains, three seeds, window
// 30 <= t <= 100; the stiff run costs 1/t_c steps per unit time), or at the study's size with
// GRANJET_STABILITY_FE1_FULL=1 in the environment (strip 30 d, 8000 grains, one seed, window
// 180 <= t <= 300: about 4 minutes of CPU for t_c = 0.01 alone). T_g(t) is sampled every 0.25:
// T_g = sum m |v - <v>|^2 / (2 N) over the grains whose centres lie in layer (a)
// (0 < x - wall surface <= 5 d) and -dy < y < 0 (dy = R_tar/5, as in spec §6).
// Burst measures, per seed, then averaged over the seeds:
// - CV: the coefficient of variation std/mean of the samples;
// - max/median of the samples;
// - block CV: the CV of T_g averaged over blocks of 2 d/u0 (8 samples): a burst is a collective
//   flow lasting many contact times, while the ~30-40 grains of the bin add sampling noise to
//   every single sample.
//
// Expected (FE.1): all three fall as t_c falls: soft t_c = 0.1 above stiff t_c = 0.01.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <numeric>
#include <vector>

#include "soft_dem/dem_simulator.hpp"
#include "stability_common.hpp"

namespace granjet::stability {
namespace {

struct BurstMeasure {
  double contact_time = 0.0;
  double mean = 0.0;
  double cv = 0.0;            // std / mean of T_g(t)
  double max_over_median = 0.0;
  double block_cv = 0.0;      // of 2 d/u0 block means
  double mean_grains = 0.0;   // grains in the bin, averaged over the samples
  double seconds = 0.0;
  std::vector<double> series;
};

constexpr double kWallSurface = 0.5;  // target grains of diameter d centred on x = 0
constexpr double kLayerHeight = 5.0;  // layer (a)
constexpr double kSample = 0.25;
constexpr int kBlock = 8;  // samples per block: 2 d/u0

bool study_size() { return std::getenv("GRANJET_STABILITY_FE1_FULL") != nullptr; }

double coefficient_of_variation(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
  double var = 0.0;
  for (double v : x) var += (v - mean) * (v - mean);
  return std::sqrt(var / (n - 1.0)) / mean;
}

// T_g of the grains with centres in layer (a), -dy < y < 0; NaN when fewer than two.
double layer_a_temperature(const Particles<2>& p, double dy, int& count) {
  Vec<2> sum = Vec<2>::Zero();
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind()[i] != GrainKind::kFree) continue;
    const Vec<2>& x = p.position()[i];
    const double h = x.x() - kWallSurface;
    if (h > 0.0 && h <= kLayerHeight && x.y() > -dy && x.y() < 0.0) {
      in.push_back(i);
      sum += p.velocity()[i];
    }
  }
  count = static_cast<int>(in.size());
  if (in.size() < 2) return std::nan("");
  const Vec<2> mean = sum / static_cast<double>(in.size());
  double t = 0.0;
  for (std::size_t i : in) t += p.mass()[i] * (p.velocity()[i] - mean).squaredNorm();
  return t / (2.0 * static_cast<double>(in.size()));
}

BurstMeasure measure_bursts(double contact_time, int seed) {
  std::vector<std::string> overrides{"contact.friction=1.0",
                                     "contact.contact_time=" + std::to_string(contact_time),
                                     "run.seed=" + std::to_string(seed),
                                     "analysis.enabled=false"};
  const bool full = study_size();
  if (!full)
    for (const char* o : {"jet.diameter=20", "wall.diameter=44", "jet.grains=2000",
                          "region.radius=88", "run.t_end=100"})
      overrides.push_back(o);
  const Scene scene = shipped_scene("jet2d", overrides);
  const double window_start = full ? 180.0 : 30.0, window_end = scene.run.t_end;
  const double dy = scene.wall.diameter / 10.0;  // R_tar / 5
  Stopwatch clock;
  auto sim = dem::make_dem_simulator<2>(scene);
  BurstMeasure m;
  m.contact_time = contact_time;
  double grains = 0.0;
  for (double t = window_start; t <= window_end + 1e-9; t += kSample) {
    sim->advance_to(t);
    int count = 0;
    const double tg = layer_a_temperature(sim->particles(), dy, count);
    grains += count;
    m.series.push_back(std::isnan(tg) ? 0.0 : tg);
  }
  m.seconds = clock.seconds();
  const double n = static_cast<double>(m.series.size());
  m.mean_grains = grains / n;
  m.mean = std::accumulate(m.series.begin(), m.series.end(), 0.0) / n;
  m.cv = coefficient_of_variation(m.series);
  std::vector<double> blocks;
  for (std::size_t k = 0; k + kBlock <= m.series.size(); k += kBlock)
    blocks.push_back(
        std::accumulate(m.series.begin() + k, m.series.begin() + k + kBlock, 0.0) / kBlock);
  m.block_cv = coefficient_of_variation(blocks);
  std::vector<double> sorted = m.series;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  m.max_over_median = sorted.back() / median;
  return m;
}

TEST(Fe1Bursts, FE1_LayerATemperatureBurstsForSoftGrainsAndCalmsForStiffOnes) {
  const std::vector<int> seeds = study_size() ? std::vector<int>{1} : std::vector<int>{1, 2, 3};
  std::vector<BurstMeasure> means;  // over the seeds, per t_c
  for (double tc : {0.1, 0.05, 0.01}) {
    BurstMeasure mean;
    mean.contact_time = tc;
    for (int seed : seeds) {
      const BurstMeasure m = measure_bursts(tc, seed);
      report(cat("fe1.tc", tc, ".seed", seed),
             cat("<T_g> = ", m.mean, ", CV = ", m.cv, ", max/median = ", m.max_over_median,
                 ", block CV = ", m.block_cv, ", grains in bin ", m.mean_grains, ", ",
                 m.seconds, " s"));
      std::string series;
      for (std::size_t k = 0; k < m.series.size(); k += 4) series += cat(m.series[k], " ");
      report(cat("fe1.tc", tc, ".seed", seed, ".series_every_1"), series);
      const double w = 1.0 / static_cast<double>(seeds.size());
      mean.mean += w * m.mean;
      mean.cv += w * m.cv;
      mean.max_over_median += w * m.max_over_median;
      mean.block_cv += w * m.block_cv;
      mean.seconds += m.seconds;
    }
    report(cat("fe1.tc", tc),
           cat(study_size() ? "study size, seed 1" : "mean over seeds 1-3", ": <T_g> = ",
               mean.mean, ", CV = ", mean.cv, ", max/median = ", mean.max_over_median,
               ", block CV = ", mean.block_cv, ", ", mean.seconds, " s"));
    means.push_back(mean);
  }
  const BurstMeasure& soft = means.front();
  const BurstMeasure& stiff = means.back();
  EXPECT_GT(soft.cv, stiff.cv) << "FE.1: soft grains should flow in bursts, stiff ones not";
  EXPECT_GT(soft.max_over_median, stiff.max_over_median);
  EXPECT_GT(soft.block_cv, stiff.block_cv);
}

}  // namespace
}  // namespace granjet::stability
