#include "analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/exact_sum.hpp"

namespace granjet::analysis {
namespace {

// Counts and exact sums added up over the ranks, in place, on every rank: as integers, so the
// result is that of all the ranks' terms in one process.
void sum_over(const RankTeam& team, std::span<std::int64_t> counts, std::span<ExactSum> sums) {
  if (team.alone()) return;
  std::vector<std::int64_t> words(counts.begin(), counts.end());
  for (ExactSum& s : sums) {
    const std::span<std::int64_t> w = s.words();
    words.insert(words.end(), w.begin(), w.end());
  }
  team.sum(words);
  std::copy_n(words.begin(), counts.size(), counts.begin());
  std::span<const std::int64_t> rest = std::span<const std::int64_t>(words).subspan(counts.size());
  for (ExactSum& s : sums) {
    const std::size_t n = s.words().size();
    s = ExactSum::of_words(rest.first(n));
    rest = rest.subspan(n);
  }
}

// The powers of values of zero mean that <x^4>/<x^2>^2 needs (flatness is blind to their scale).
struct Powers {
  ExactSum second, fourth;
  void add(double x) {
    second.add(x * x);
    fourth.add(x * x * x * x);
  }
  // NaN without values.
  double flatness(std::int64_t count) const {
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    const double n = static_cast<double>(count);
    const double s = second.value() / n, f = fourth.value() / n;
    return f / (s * s);
  }
};

}  // namespace

template <int D>
std::vector<double> VelocityDistribution<D>::density_edges() {
  std::vector<double> edges(kIntervals + 1);
  for (int k = 0; k <= kIntervals; ++k) edges[k] = kRange * (2.0 * k / kIntervals - 1.0);
  return edges;
}

template <int D>
void VelocityDistribution<D>::join(const RankTeam& team) {
  statistics_ = statistics(team);
}

template <int D>
auto VelocityDistribution<D>::current() const -> const Statistics& {
  if (!statistics_) statistics_ = statistics(RankTeam());
  return *statistics_;
}

template <int D>
auto VelocityDistribution<D>::statistics(const RankTeam& team) const -> Statistics {
  const auto at = [&](int component, int bin) { return component * bins_ + bin; };
  // Each bin's mean and population deviation, so each bin's scaled values have exactly unit
  // variance.
  std::vector<std::int64_t> count(bins_, 0);
  std::vector<ExactSum> moments(2 * D * bins_);  // per component and bin: sum, sum of squares
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    ++count[bin_[k]];
    for (int a = 0; a < D; ++a) {
      const double v = velocity_[k][a];
      moments[2 * at(a, bin_[k])].add(v);
      moments[2 * at(a, bin_[k]) + 1].add(v * v);
    }
  }
  sum_over(team, count, moments);
  std::vector<double> mean(D * bins_, 0.0), sd(D * bins_, 0.0);
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < bins_; ++b) {
      const double n = static_cast<double>(count[b]);
      const int i = at(a, b);
      mean[i] = n > 0.0 ? moments[2 * i].value() / n : 0.0;
      const double var = n > 1.0 ? moments[2 * i + 1].value() / n - mean[i] * mean[i] : 0.0;
      sd[i] = std::sqrt(std::max(var, 0.0));
    }

  // Per component: each bin's scaled values, then all of them pooled, then the region's
  // fluctuations (one scale); their counts; the density's counts.
  const int sets = bins_ + 2;
  std::vector<Powers> powers(D * sets);
  std::vector<std::int64_t> counts(D * sets + D * kIntervals, 0);
  const std::vector<double> edges = density_edges();
  for (std::size_t k = 0; k < bin_.size(); ++k) {
    const int b = bin_[k];
    for (int a = 0; a < D; ++a) {
      const int i = at(a, b);
      if (!(sd[i] > 0.0)) continue;
      const double u = velocity_[k][a] - mean[i], c = u / sd[i];
      for (int set : {b, bins_}) {
        powers[a * sets + set].add(c);
        ++counts[a * sets + set];
      }
      powers[a * sets + bins_ + 1].add(u);
      ++counts[a * sets + bins_ + 1];
      const auto it = std::upper_bound(edges.begin(), edges.end(), c);
      if (it != edges.begin() && it != edges.end())
        ++counts[D * sets + a * kIntervals + (it - edges.begin() - 1)];
    }
  }
  std::vector<ExactSum> sums;
  for (const Powers& p : powers) sums.insert(sums.end(), {p.second, p.fourth});
  sum_over(team, counts, sums);

  Statistics s;
  for (int a = 0; a < D; ++a) {
    const auto flatness_of = [&](int set) {
      const int i = a * sets + set;
      return Powers{sums[2 * i], sums[2 * i + 1]}.flatness(counts[i]);
    };
    for (int set = 0; set <= bins_; ++set) s.flatness_bin[a].push_back(flatness_of(set));
    s.flatness_region[a] = flatness_of(bins_ + 1);
    const std::int64_t scaled = counts[a * sets + bins_];
    s.density[a].assign(kIntervals, 0.0);
    if (scaled == 0) continue;
    for (int k = 0; k < kIntervals; ++k)
      s.density[a][k] = static_cast<double>(counts[D * sets + a * kIntervals + k]) /
                        (static_cast<double>(scaled) * (edges[k + 1] - edges[k]));
  }
  return s;
}

template <int D>
double VelocityDistribution<D>::flatness(int component, int bin) const {
  return current().flatness_bin[component][bin < 0 ? bins_ : bin];
}

template <int D>
double VelocityDistribution<D>::flatness_region(int component) const {
  return current().flatness_region[component];
}

template <int D>
std::vector<double> VelocityDistribution<D>::density(int component) const {
  return current().density[component];
}

template class VelocityDistribution<2>;
template class VelocityDistribution<3>;

}  // namespace granjet::analysis
