// Recursive coordinate bisection (Berger and Bokhari, IEEE Trans. Comput. C-36, 570 (1987)):
// weighted points shared among `parts` regions of space so that each region's weight is about
// the mean. Each cut is a plane across the longest side of its points' bounding box, at the
// weighted share of the parts on either side (parts = a + b, a = parts / 2, the left side gets
// a / parts of the weight). Meant for the soft DEM's domain decomposition over MPI ranks, one
// part per rank, each grain weighted by its measured work, so that a jet's impact region,
// where contacts crowd, is cut finer than its column; for_each_part_near names the parts that
// need a grain as a ghost. Deterministic: along an axis points are
// ordered by (coordinate, index), and a cut falls only between distinct coordinates, so that
// part_of(x) gives every point of the build the part the build gave it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/dim.hpp"

namespace granjet {

template <int D>
class RecursiveBisection {
 public:
  // `parts` >= 1 regions for points `x` with weights `weight` (same length, each >= 0).
  RecursiveBisection(std::span<const Vec<D>> x, std::span<const double> weight, int parts)
      : parts_(parts), part_(x.size(), 0) {
    if (parts < 1) throw std::invalid_argument("recursive bisection: parts must be at least 1");
    if (weight.size() != x.size())
      throw std::invalid_argument("recursive bisection: " + std::to_string(weight.size()) +
                                  " weights for " + std::to_string(x.size()) + " points");
    std::vector<std::uint32_t> points(x.size());
    std::iota(points.begin(), points.end(), 0u);
    build(x, weight, points, 0, points.size(), 0, parts);
  }

  int parts() const { return parts_; }
  // The part of each point of the build, by index.
  const std::vector<int>& part() const { return part_; }

  // The part whose region holds position p (a point on a cut belongs to the upper side).
  int part_of(const Vec<D>& p) const {
    int node = 0;
    while (nodes_[node].axis >= 0)
      node = p[nodes_[node].axis] < nodes_[node].at ? nodes_[node].lower : nodes_[node].upper;
    return nodes_[node].part;
  }

  // Calls visit(part) for every part whose region comes closer than `reach` to position p, its
  // own included (each once, in the order of the parts). A grain within reach of a grain of
  // another part is within reach of that part's region, so the parts visited for a grain at
  // reach = the largest interaction range are those that need it as a ghost. (Open space: a
  // periodic box's images are not looked for.)
  template <class Visit>
  void for_each_part_near(const Vec<D>& p, double reach, Visit&& visit) const {
    const double inf = std::numeric_limits<double>::infinity();
    near(0, p, reach * reach, Vec<D>::Constant(-inf), Vec<D>::Constant(inf), visit);
  }

 private:
  // Descends into node's region [low, high) while it is closer than sqrt(reach2) to p.
  template <class Visit>
  void near(int node, const Vec<D>& p, double reach2, Vec<D> low, Vec<D> high, Visit& visit) const {
    const Vec<D> gap = (low - p).cwiseMax(p - high).cwiseMax(0.0);
    if (!(gap.squaredNorm() < reach2)) return;
    const Node& n = nodes_[node];
    if (n.axis < 0) {
      visit(n.part);
      return;
    }
    const double top = high[n.axis];
    high[n.axis] = n.at;
    near(n.lower, p, reach2, low, high, visit);
    high[n.axis] = top;
    low[n.axis] = n.at;
    near(n.upper, p, reach2, low, high, visit);
  }

  struct Node {
    int axis = -1;  // -1: a leaf, all of whose region is `part`
    double at = 0.0;
    int lower = -1, upper = -1;
    int part = 0;
  };

  // Node for points[begin, end), which get parts [first_part, first_part + parts); its index.
  int build(std::span<const Vec<D>> x, std::span<const double> weight,
            std::vector<std::uint32_t>& points, std::size_t begin, std::size_t end, int first_part,
            int parts) {
    const int node = static_cast<int>(nodes_.size());
    nodes_.push_back({-1, 0.0, -1, -1, first_part});
    const auto leaf = [&] {
      for (std::size_t k = begin; k < end; ++k) part_[points[k]] = first_part;
      return node;
    };
    if (parts == 1 || end - begin < 2) return leaf();
    const int lower_parts = parts / 2;
    // The axes, longest side of the points' bounding box first.
    Vec<D> low = x[points[begin]], high = low;
    for (std::size_t k = begin; k < end; ++k) {
      low = low.cwiseMin(x[points[k]]);
      high = high.cwiseMax(x[points[k]]);
    }
    std::array<int, D> axes;
    std::iota(axes.begin(), axes.end(), 0);
    const Vec<D> side = high - low;
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return side[a] > side[b]; });
    for (int axis : axes) {
      const auto first = points.begin() + static_cast<std::ptrdiff_t>(begin);
      const auto last = points.begin() + static_cast<std::ptrdiff_t>(end);
      std::sort(first, last, [&](std::uint32_t a, std::uint32_t b) {
        return x[a][axis] < x[b][axis] || (x[a][axis] == x[b][axis] && a < b);
      });
      const std::size_t cut = cut_between(x, weight, points, begin, end, axis,
                                          static_cast<double>(lower_parts) / parts);
      if (cut == begin) continue;  // all points share this coordinate
      const double below = x[points[cut - 1]][axis], above = x[points[cut]][axis];
      const double middle = 0.5 * (below + above);
      const int lower = build(x, weight, points, begin, cut, first_part, lower_parts);
      const int upper =
          build(x, weight, points, cut, end, first_part + lower_parts, parts - lower_parts);
      nodes_[node] = {axis, middle > below ? middle : above, lower, upper, first_part};
      return node;
    }
    return leaf();  // coincident points: one part holds them all
  }

  // Where points[begin, end), sorted along `axis`, are cut: the boundary between distinct
  // coordinates whose lower side's weight is closest to `fraction` of the whole (the lower of
  // two equally close); begin if no such boundary exists.
  static std::size_t cut_between(std::span<const Vec<D>> x, std::span<const double> weight,
                                 const std::vector<std::uint32_t>& points, std::size_t begin,
                                 std::size_t end, int axis, double fraction) {
    double total = 0.0;
    for (std::size_t k = begin; k < end; ++k) total += weight[points[k]];
    const double target = fraction * total;
    std::size_t best = begin;
    double best_miss = 0.0;
    double lower_weight = 0.0;
    for (std::size_t k = begin + 1; k < end; ++k) {
      lower_weight += weight[points[k - 1]];
      if (!(x[points[k - 1]][axis] < x[points[k]][axis])) continue;
      const double miss = std::abs(lower_weight - target);
      if (best == begin || miss < best_miss) {
        best = k;
        best_miss = miss;
      }
    }
    return best;
  }

  int parts_;
  std::vector<int> part_;
  std::vector<Node> nodes_;
};

// The load imbalance of a share-out: the heaviest part's weight over the mean part's (1 for a
// perfect one). part[i] in [0, parts) is point i's part.
inline double imbalance(std::span<const int> part, std::span<const double> weight, int parts) {
  std::vector<double> load(parts, 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < part.size(); ++i) {
    load[part[i]] += weight[i];
    total += weight[i];
  }
  if (!(total > 0.0)) return 1.0;
  return *std::max_element(load.begin(), load.end()) / (total / parts);
}

}  // namespace granjet
