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
// the study's convention): T_a's m cancels. The moments are exact sums (core/exact_sum.hpp), so
// the values' order does not change a bit of them.
#pragma once

#include <span>
#include <vector>

#include "core/dim.hpp"
#include "core/rank_team.hpp"

namespace granjet::analysis {

template <int D>
class VelocityDistribution {
 public:
  explicit VelocityDistribution(int bins) : bins_(bins) {}

  void add(int bin, const Vec<D>& velocity) {
    bin_.push_back(bin);
    velocity_.push_back(velocity);
  }
  std::size_t size() const { return bin_.size(); }
  // Over MPI ranks: every rank's values join rank 0's (in rank order; the order changes no
  // moment), and the other ranks keep none. Collective.
  void join(const RankTeam& team);

  // Fluctuations c of one component scaled by their bin's standard deviation, pooled over all
  // bins or of one bin (bin >= 0). Bins with fewer than two values or no spread contribute
  // nothing.
  std::vector<double> scaled(int component, int bin = -1) const;
  // <c^4>/<c^2>^2 of scaled(component, bin), each bin's own T_a; NaN without values.
  double flatness(int component, int bin = -1) const;
  // <c^4>/<c^2>^2 with one T_a for the whole region: the fluctuations about each bin's mean of
  // the same bins as scaled(), all scaled by one deviation. NaN without values.
  double flatness_region(int component) const;
  // Probability density of the pooled scaled values per interval of `edges` (ascending); values
  // outside the edges count in the normalisation, so the density integrates to the fraction
  // inside.
  std::vector<double> density(int component, std::span<const double> edges) const;

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("bin", bin_);
    v("velocity", velocity_);
  }

 private:
  struct BinMoments {
    std::vector<double> mean, sd;
  };
  BinMoments moments(int component) const;

  int bins_;
  std::vector<int> bin_;
  std::vector<Vec<D>> velocity_;
};

extern template class VelocityDistribution<2>;
extern template class VelocityDistribution<3>;

}  // namespace granjet::analysis
