// Recursive coordinate bisection (Berger and Bokhari, IEEE Trans. Comput. C-36, 570 (1987)):
// weighted points shared among `parts` regions of space so that each region's weight is about
// the mean. Each cut is a plane across the longest side of its points' bounding box, at the
// weighted share of the parts on either side (parts = a + b, a = parts / 2, the left side gets
// a / parts of the weight). Meant for the soft DEM's domain decomposition over MPI ranks, one
// part per rank, each grain weighted by its measured work, so that a jet's impact region,
// where contacts crowd, is cut finer than its column; for_each_part_near names the parts that
// need a grain as a ghost. LengthwiseCuts keeps the first levels' cuts along one axis (their
// planes contain it), for work that travels along it. Deterministic: along an axis points are
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

// The first `levels` levels of a bisection cut across the longest side other than `axis`, so
// that each of their planes contains the axis direction; deeper levels, or a node whose points
// all share the other coordinates, cut across the longest side. Work that travels along the
// axis (a compression front climbing a jet's column) then stays shared by the parts on either
// side of those cuts rather than crossing from one part into the next.
struct LengthwiseCuts {
  int axis = 0;
  int levels = 0;  // 0: every cut across the longest side
};

template <int D>
class RecursiveBisection {
 public:
  // `parts` >= 1 regions for points `x` with weights `weight` (same length, each >= 0).
  RecursiveBisection(std::span<const Vec<D>> x, std::span<const double> weight, int parts,
                     LengthwiseCuts lengthwise = {})
      : RecursiveBisection(parts, x.size(), lengthwise) {
    check(x.size(), weight.size(), parts);
    std::vector<std::uint32_t> points(x.size());
    std::iota(points.begin(), points.end(), 0u);
    build(x, weight, points, 0, points.size(), 0, parts, 0);
  }

  // The same share-out of points spread over the ranks of `team` (each passes its own; every
  // rank gets the same regions), with no rank holding more than its own points: each cut is
  // found by narrowing a histogram of the weight along its axis, kRounds times over kBins
  // bins, each summed over the ranks in integer units of the largest weight / 2^30 (exact in
  // any order, so alike on every rank, and the same regions for any split of the points over
  // the ranks). A cut falls on a bin edge within side / kBins^kRounds of the weighted share,
  // not between two points as in the build above. part() gives this rank's points' parts.
  // Team: max, min (std::span<double>) and sum (std::span<std::int64_t>) over the ranks, in
  // place (core/rank_team.hpp).
  template <class Team>
  static RecursiveBisection over_ranks(const Team& team, std::span<const Vec<D>> x,
                                       std::span<const double> weight, int parts,
                                       LengthwiseCuts lengthwise = {});

  static constexpr int kBins = 64;
  static constexpr int kRounds = 4;

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

  // The part of p (part_of), calling visit(part) first for every other part whose region comes
  // closer than `reach` to p, as for_each_part_near would. Most points of a part lie farther
  // than `reach` from every cut on their way down the tree, and no other part is near them (a
  // part that branches off at a cut lies beyond it): they cost one descent, not a search.
  template <class Visit>
  int part_and_others_near(const Vec<D>& p, double reach, Visit&& visit) const {
    int node = 0;
    bool alone = true;
    while (nodes_[node].axis >= 0) {
      const Node& n = nodes_[node];
      alone &= !(std::abs(p[n.axis] - n.at) < reach);
      node = p[n.axis] < n.at ? n.lower : n.upper;
    }
    const int own = nodes_[node].part;
    if (!alone)
      for_each_part_near(p, reach, [&](int part) {
        if (part != own) visit(part);
      });
    return own;
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

  RecursiveBisection(int parts, std::size_t points, LengthwiseCuts lengthwise)
      : parts_(parts), part_(points, 0), lengthwise_(lengthwise) {
    if (lengthwise.levels > 0 && (lengthwise.axis < 0 || lengthwise.axis >= D))
      throw std::invalid_argument("recursive bisection: lengthwise axis " +
                                  std::to_string(lengthwise.axis) + " outside 0.." +
                                  std::to_string(D - 1));
  }

  // The axes in the order a node at `level` with bounding box sides `side` tries them: longest
  // side first, the lengthwise axis last while level < lengthwise_.levels (the lowest axis of
  // equal ones first).
  std::array<int, D> axes_in_order(const Vec<D>& side, int level) const {
    const auto last = [&](int a) { return level < lengthwise_.levels && a == lengthwise_.axis; };
    std::array<int, D> axes;
    std::iota(axes.begin(), axes.end(), 0);
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) {
      return last(a) != last(b) ? last(b) : side[a] > side[b];
    });
    return axes;
  }
  static void check(std::size_t points, std::size_t weights, int parts) {
    if (parts < 1) throw std::invalid_argument("recursive bisection: parts must be at least 1");
    if (weights != points)
      throw std::invalid_argument("recursive bisection: " + std::to_string(weights) +
                                  " weights for " + std::to_string(points) + " points");
  }

  // Node for points[begin, end), which get parts [first_part, first_part + parts); its index.
  int build(std::span<const Vec<D>> x, std::span<const double> weight,
            std::vector<std::uint32_t>& points, std::size_t begin, std::size_t end, int first_part,
            int parts, int level) {
    const int node = static_cast<int>(nodes_.size());
    nodes_.push_back({-1, 0.0, -1, -1, first_part});
    const auto leaf = [&] {
      for (std::size_t k = begin; k < end; ++k) part_[points[k]] = first_part;
      return node;
    };
    if (parts == 1 || end - begin < 2) return leaf();
    const int lower_parts = parts / 2;
    Vec<D> low = x[points[begin]], high = low;
    for (std::size_t k = begin; k < end; ++k) {
      low = low.cwiseMin(x[points[k]]);
      high = high.cwiseMax(x[points[k]]);
    }
    for (int axis : axes_in_order(high - low, level)) {
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
      const int lower = build(x, weight, points, begin, cut, first_part, lower_parts, level + 1);
      const int upper = build(x, weight, points, cut, end, first_part + lower_parts,
                              parts - lower_parts, level + 1);
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
  LengthwiseCuts lengthwise_;
  std::vector<Node> nodes_;
};

template <int D>
template <class Team>
RecursiveBisection<D> RecursiveBisection<D>::over_ranks(const Team& team, std::span<const Vec<D>> x,
                                                        std::span<const double> weight, int parts,
                                                        LengthwiseCuts lengthwise) {
  check(x.size(), weight.size(), parts);
  RecursiveBisection rcb(parts, x.size(), lengthwise);
  const std::size_t n = x.size();
  std::vector<double> largest{0.0};
  for (double w : weight) largest[0] = std::max(largest[0], w);
  team.max(largest);
  const double unit = largest[0] > 0.0 ? std::ldexp(largest[0], -30) : 1.0;
  std::vector<std::int64_t> units(n);
  for (std::size_t i = 0; i < n; ++i) units[i] = std::llround(weight[i] / unit);

  // The nodes still to cut, level by level: all of a level's nodes share each collective call.
  struct Open {
    int node, first_part, parts;
  };
  rcb.nodes_.push_back({-1, 0.0, -1, -1, 0});
  std::vector<int> node_of(n, 0);
  std::vector<Open> open;
  if (parts > 1) open.push_back({0, 0, parts});
  const double inf = std::numeric_limits<double>::infinity();
  for (int level = 0; !open.empty(); ++level) {
    const std::size_t m = open.size();
    std::vector<int> slot(rcb.nodes_.size(), -1);
    for (std::size_t k = 0; k < m; ++k) slot[open[k].node] = static_cast<int>(k);
    // Each open node's bounding box, weight and point count.
    std::vector<double> low(m * D, inf), high(m * D, -inf);
    std::vector<std::int64_t> totals(2 * m, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const int k = slot[node_of[i]];
      if (k < 0) continue;
      for (int a = 0; a < D; ++a) {
        low[k * D + a] = std::min(low[k * D + a], x[i][a]);
        high[k * D + a] = std::max(high[k * D + a], x[i][a]);
      }
      totals[2 * k] += units[i];
      totals[2 * k + 1] += 1;
    }
    team.min(low);
    team.max(high);
    team.sum(totals);
    // Along the first axis of axes_in_order whose side is not empty, between the box's low side
    // and just above its high one; a node of fewer than two points, or of coincident ones, is a
    // leaf. below: the weight under the bracket [lo, hi).
    std::vector<int> axis(m, -1);
    std::vector<double> lo(m), hi(m), target(m);
    std::vector<std::int64_t> below(m, 0);
    for (std::size_t k = 0; k < m; ++k) {
      Vec<D> side;
      for (int a = 0; a < D; ++a) side[a] = high[k * D + a] - low[k * D + a];
      const std::array<int, D> axes = rcb.axes_in_order(side, level);
      const auto best =
          std::find_if(axes.begin(), axes.end(), [&](int a) { return side[a] > 0.0; });
      if (totals[2 * k + 1] < 2 || best == axes.end()) continue;
      axis[k] = *best;
      lo[k] = low[k * D + *best];
      hi[k] = std::nextafter(high[k * D + *best], inf);
      target[k] = static_cast<double>(totals[2 * k]) * (open[k].parts / 2) / open[k].parts;
    }
    const auto edge = [&](std::size_t k, int b) {
      return b == kBins ? hi[k] : lo[k] + (hi[k] - lo[k]) * b / kBins;
    };
    // The bin of coordinate c in node k's bracket, by the same edges every rank computes.
    const auto bin_of = [&](std::size_t k, double c) {
      int b = std::clamp(static_cast<int>((c - lo[k]) / (hi[k] - lo[k]) * kBins), 0, kBins - 1);
      while (b > 0 && c < edge(k, b)) --b;
      while (b < kBins - 1 && !(c < edge(k, b + 1))) ++b;
      return b;
    };
    for (int round = 0; round < kRounds; ++round) {
      std::vector<std::int64_t> histogram(m * kBins, 0);
      for (std::size_t i = 0; i < n; ++i) {
        const int k = slot[node_of[i]];
        if (k < 0 || axis[k] < 0) continue;
        const double c = x[i][axis[k]];
        if (c < lo[k] || !(c < hi[k])) continue;
        histogram[k * kBins + bin_of(k, c)] += units[i];
      }
      team.sum(histogram);
      // Narrow each bracket to the bin where the weight below crosses the target.
      for (std::size_t k = 0; k < m; ++k) {
        if (axis[k] < 0 || !(lo[k] < edge(k, 1))) continue;  // too narrow to split again
        std::int64_t under = below[k];
        int b = 0;
        while (b < kBins - 1 && static_cast<double>(under + histogram[k * kBins + b]) <= target[k])
          under += histogram[k * kBins + b++];
        const double new_lo = edge(k, b), new_hi = edge(k, b + 1);
        lo[k] = new_lo;
        hi[k] = new_hi;
        below[k] = under;
        if (round + 1 == kRounds) {  // the closer edge: the lower one of two equally close
          const double miss_low = std::abs(static_cast<double>(under) - target[k]);
          const double miss_high =
              std::abs(static_cast<double>(under + histogram[k * kBins + b]) - target[k]);
          if (miss_high < miss_low) lo[k] = new_hi;
        }
      }
    }
    // Cut at lo: the points below it go to the lower parts.
    std::vector<Open> next;
    std::vector<int> lower_of(m, -1);
    for (std::size_t k = 0; k < m; ++k) {
      if (axis[k] < 0) continue;
      const Open& o = open[k];
      const int lower_parts = o.parts / 2;
      const int lower = static_cast<int>(rcb.nodes_.size());
      rcb.nodes_.push_back({-1, 0.0, -1, -1, o.first_part});
      rcb.nodes_.push_back({-1, 0.0, -1, -1, o.first_part + lower_parts});
      rcb.nodes_[o.node] = {axis[k], lo[k], lower, lower + 1, o.first_part};
      lower_of[k] = lower;
      if (lower_parts > 1) next.push_back({lower, o.first_part, lower_parts});
      if (o.parts - lower_parts > 1)
        next.push_back({lower + 1, o.first_part + lower_parts, o.parts - lower_parts});
    }
    for (std::size_t i = 0; i < n; ++i) {
      const int k = slot[node_of[i]];
      if (k < 0 || axis[k] < 0) continue;
      node_of[i] = lower_of[k] + (x[i][axis[k]] < lo[k] ? 0 : 1);
    }
    open = std::move(next);
  }
  for (std::size_t i = 0; i < n; ++i) rcb.part_[i] = rcb.nodes_[node_of[i]].part;
  return rcb;
}

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
