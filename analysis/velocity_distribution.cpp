#include "analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace granjet::analysis {

template <int D>
std::vector<double> VelocityDistribution<D>::scaled(int component, int bin) const {
  std::vector<double> count(bins_, 0.0), sum(bins_, 0.0), squares(bins_, 0.0);
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    const double v = velocity_[k][component];
    count[bin_[k]] += 1.0;
    sum[bin_[k]] += v;
    squares[bin_[k]] += v * v;
  }
  std::vector<double> mean(bins_), sd(bins_);
  for (int b = 0; b < bins_; ++b) {
    mean[b] = count[b] > 0.0 ? sum[b] / count[b] : 0.0;
    // The population deviation, so each bin's scaled values have exactly unit variance.
    const double var = count[b] > 1.0 ? squares[b] / count[b] - mean[b] * mean[b] : 0.0;
    sd[b] = std::sqrt(std::max(var, 0.0));
  }
  std::vector<double> out;
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    const int b = bin_[k];
    if ((bin < 0 || b == bin) && sd[b] > 0.0)
      out.push_back((velocity_[k][component] - mean[b]) / sd[b]);
  }
  return out;
}

template <int D>
double VelocityDistribution<D>::flatness(int component, int bin) const {
  const std::vector<double> c = scaled(component, bin);
  if (c.empty()) return std::numeric_limits<double>::quiet_NaN();
  double c2 = 0.0, c4 = 0.0;
  for (double x : c) {
    c2 += x * x;
    c4 += x * x * x * x;
  }
  c2 /= c.size();
  c4 /= c.size();
  return c4 / (c2 * c2);
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
