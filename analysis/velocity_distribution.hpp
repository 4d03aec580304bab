// Per-component velocity distributions of the grains in the measurement bins (model §6): each
// grain's fluctuation u = v - (mean velocity of its bin), as in T_g, scaled to unit variance;
// flatness <c^4>/<c^2>^2 (Gaussian 3, exponential 6). The local-frame velocities of the window
// are kept, so the means and deviations are those of the whole window, as for T_alpha.
//
// The study scales by v_a0 = sqrt(2 T_a/m) without saying whether T_a is each bin's or one value
// for the whole measured region; both are reported (T5.1). Per bin, every bin contributes a
// unit-variance sample and a mixture of bins at different temperatures still has the flatness
// of its shape; per region, one scale for all, so such a mixture adds flatness. The flatness
// does not depend on the constant factor of the scale, and all grains weigh the same (mass m,
// the study's convention): T_a's m cancels.
//
// Every statistic is made of counts and exact sums (core/exact_sum.hpp): the values' order does
// not change a bit of them, and over MPI ranks each rank keeps the values of its own grains and
// the ranks add up their sums as integers (join), first the bins' moments, then the scaled
// values' powers and the density's counts. No rank gathers the values.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "core/dim.hpp"
#include "core/rank_team.hpp"

namespace granjet::analysis {

template <int D>
class VelocityDistribution {
 public:
  // The density's intervals of the scaled velocity: kIntervals of one width over
  // [-kRange, kRange].
  static constexpr int kIntervals = 48;
  static constexpr double kRange = 6.0;
  static std::vector<double> density_edges();

  explicit VelocityDistribution(int bins) : bins_(bins) {}

  void add(int bin, const Vec<D>& velocity) {
    bin_.push_back(bin);
    velocity_.push_back(velocity);
    statistics_.reset();
  }
  // This rank's values.
  std::size_t size() const { return bin_.size(); }
  // Over MPI ranks (collective): the statistics below, of every rank's values, until the next
  // add(). Each rank keeps its own values.
  void join(const RankTeam& team);

  // <c^4>/<c^2>^2 of the fluctuations c of one component, each scaled by its bin's standard
  // deviation (each bin's own T_a), pooled over all bins or of one bin (bin >= 0). Bins with
  // fewer than two values or no spread contribute nothing; NaN without values.
  double flatness(int component, int bin = -1) const;
  // <c^4>/<c^2>^2 with one T_a for the whole region: the fluctuations about each bin's mean of
  // the same bins as flatness(), all scaled by one deviation. NaN without values.
  double flatness_region(int component) const;
  // Probability density of the pooled scaled values per interval of density_edges(); values
  // outside the edges count in the normalisation, so the density integrates to the fraction
  // inside.
  std::vector<double> density(int component) const;

  // This rank's values (over ranks, its share of a checkpoint).
  template <class Visitor>
  void visit_state(Visitor& v) {
    v("bin", bin_);
    v("velocity", velocity_);
    statistics_.reset();
  }

 private:
  struct Statistics {
    std::array<std::vector<double>, D> flatness_bin;  // each bin's, then all bins pooled
    std::array<double, D> flatness_region{};
    std::array<std::vector<double>, D> density;
  };
  // Collective over `team`: every rank's values.
  Statistics statistics(const RankTeam& team) const;
  // Those of the last join, or else of this rank's values.
  const Statistics& current() const;

  int bins_;
  std::vector<int> bin_;
  std::vector<Vec<D>> velocity_;
  mutable std::optional<Statistics> statistics_;
};

extern template class VelocityDistribution<2>;
extern template class VelocityDistribution<3>;

}  // namespace granjet::analysis
