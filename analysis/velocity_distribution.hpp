// Per-component velocity distributions of the grains in the measurement bins (spec §6): each
// grain's fluctuation u = v - (mean velocity of its bin) is scaled by the bin's standard
// deviation of that component, so every bin contributes a unit-variance sample; flatness
// <c^4>/<c^2>^2 (Gaussian 3, exponential 6). The local-frame velocities of the window are kept,
// so the means and deviations are those of the whole window, as for T_alpha.
#pragma once

#include <span>
#include <vector>

#include "core/dim.hpp"

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

  // Scaled fluctuations c of one component, pooled over all bins or of one bin (bin >= 0).
  // Bins with fewer than two values or no spread contribute nothing.
  std::vector<double> scaled(int component, int bin = -1) const;
  // <c^4>/<c^2>^2 of scaled(component, bin); NaN without values.
  double flatness(int component, int bin = -1) const;
  // Probability density of the pooled scaled values per interval of `edges` (ascending); values
  // outside the edges count in the normalisation, so the density integrates to the fraction
  // inside.
  std::vector<double> density(int component, std::span<const double> edges) const;

 private:
  int bins_;
  std::vector<int> bin_;
  std::vector<Vec<D>> velocity_;
};

extern template class VelocityDistribution<2>;
extern template class VelocityDistribution<3>;

}  // namespace granjet::analysis
