#include "analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/exact_sum.hpp"

namespace granjet::analysis {
namespace {

// <x^4>/<x^2>^2 of values of zero mean (flatness is blind to their scale); NaN without values.
// Exact sums: the same bits in any order of the values.
double fourth_over_second_squared(const std::vector<double>& x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  ExactSum x2, x4;
  for (double v : x) {
    x2.add(v * v);
    x4.add(v * v * v * v);
  }
  const double second = x2.value() / x.size(), fourth = x4.value() / x.size();
  return fourth / (second * second);
}

}  // namespace

template <int D>
typename VelocityDistribution<D>::BinMoments VelocityDistribution<D>::moments(int component) const {
  std::vector<double> count(bins_, 0.0);
  std::vector<ExactSum> sum(bins_), squares(bins_);
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    const double v = velocity_[k][component];
    count[bin_[k]] += 1.0;
    sum[bin_[k]].add(v);
    squares[bin_[k]].add(v * v);
  }
  BinMoments m{std::vector<double>(bins_), std::vector<double>(bins_)};
  for (int b = 0; b < bins_; ++b) {
    m.mean[b] = count[b] > 0.0 ? sum[b].value() / count[b] : 0.0;
    // The population deviation, so each bin's scaled values have exactly unit variance.
    const double var = count[b] > 1.0 ? squares[b].value() / count[b] - m.mean[b] * m.mean[b] : 0.0;
    m.sd[b] = std::sqrt(std::max(var, 0.0));
  }
  return m;
}

template <int D>
void VelocityDistribution<D>::join(const RankTeam& team) {
  if (team.alone()) return;
  std::vector<double> mine;
  mine.reserve(D * velocity_.size());
  for (const Vec<D>& v : velocity_) mine.insert(mine.end(), v.data(), v.data() + D);
  bin_ = team.gather<int>(bin_);  // rank 0: all of them; the others: none
  const std::vector<double> all = team.gather<double>(mine);
  velocity_.resize(all.size() / D);
  for (std::size_t k = 0; k < velocity_.size(); ++k)
    for (int d = 0; d < D; ++d) velocity_[k][d] = all[D * k + d];
}

template <int D>
std::vector<double> VelocityDistribution<D>::scaled(int component, int bin) const {
  const BinMoments m = moments(component);
  std::vector<double> out;
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    const int b = bin_[k];
    if ((bin < 0 || b == bin) && m.sd[b] > 0.0)
      out.push_back((velocity_[k][component] - m.mean[b]) / m.sd[b]);
  }
  return out;
}

template <int D>
double VelocityDistribution<D>::flatness(int component, int bin) const {
  return fourth_over_second_squared(scaled(component, bin));
}

template <int D>
double VelocityDistribution<D>::flatness_region(int component) const {
  const BinMoments m = moments(component);
  std::vector<double> u;  // unscaled: one scale for all leaves the flatness as it is
  for (std::size_t k = 0; k < bin_.size(); ++k)
    if (m.sd[bin_[k]] > 0.0) u.push_back(velocity_[k][component] - m.mean[bin_[k]]);
  return fourth_over_second_squared(u);
}

template <int D>
std::vector<double> VelocityDistribution<D>::density(int component,
                                                     std::span<const double> edges) const {
  const std::vector<double> c = scaled(component);
  std::vector<double> out(edges.size() > 0 ? edges.size() - 1 : 0, 0.0);
  if (c.empty() || out.empty()) return out;
  for (double x : c) {
    const auto it = std::upper_bound(edges.begin(), edges.end(), x);
    if (it == edges.begin() || it == edges.end()) continue;
    out[it - edges.begin() - 1] += 1.0;
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k] /= c.size() * (edges[k + 1] - edges[k]);
  return out;
}

template class VelocityDistribution<2>;
template class VelocityDistribution<3>;

}  // namespace granjet::analysis
