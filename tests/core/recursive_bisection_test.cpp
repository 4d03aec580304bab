// RecursiveBisection: every point in the part part_of gives its position, parts balanced by
// weight (not by count), cuts across the longest side (or, in lengthwise levels, along an
// axis), and coincident points kept together;
// the same of the build over ranks (over_ranks, here on one rank; tests/ranks splits the points
// over several).
#include "core/recursive_bisection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <vector>

#include "core/rank_team.hpp"

namespace granjet {
namespace {

template <int D>
std::vector<Vec<D>> random_points(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::vector<Vec<D>> x(n);
  for (Vec<D>& p : x)
    for (int a = 0; a < D; ++a) p[a] = u(rng);
  return x;
}

std::vector<double> random_weights(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 3.0);
  std::vector<double> w(n);
  for (double& value : w) value = u(rng);
  return w;
}

// Every point's part is in range and is the part of its position, and no part is empty.
template <int D>
void expect_every_point_in_the_part_of_its_position(const RecursiveBisection<D>& rcb,
                                                    const std::vector<Vec<D>>& x) {
  const int parts = rcb.parts();
  std::vector<int> count(parts, 0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_GE(rcb.part()[i], 0);
    ASSERT_LT(rcb.part()[i], parts);
    EXPECT_EQ(rcb.part_of(x[i]), rcb.part()[i]) << "point " << i << ", " << parts << " parts";
    ++count[rcb.part()[i]];
  }
  for (int c : count) EXPECT_GT(c, 0) << parts << " parts";
}

// Every point in the part of its position, and the share-out the same when built again.
TEST(RecursiveBisection, PartOfAPointsPositionIsItsPart) {
  const std::vector<Vec<3>> x = random_points<3>(2000, 7);
  const std::vector<double> w = random_weights(x.size(), 11);
  for (int parts = 1; parts <= 7; ++parts) {
    const RecursiveBisection<3> rcb(x, w, parts);
    expect_every_point_in_the_part_of_its_position(rcb, x);
    EXPECT_EQ(RecursiveBisection<3>(x, w, parts).part(), rcb.part());
  }
}

// Equal weights: each part within a few points of n / parts, for parts that are not powers of
// two too (each cut misses its share by at most half a point's weight).
TEST(RecursiveBisection, EqualWeightsGiveEqualCounts) {
  const std::vector<Vec<2>> x = random_points<2>(1000, 3);
  const std::vector<double> w(x.size(), 1.0);
  for (int parts : {2, 3, 4, 5, 8}) {
    const RecursiveBisection<2> rcb(x, w, parts);
    std::vector<int> count(parts, 0);
    for (int p : rcb.part()) ++count[p];
    for (int c : count) EXPECT_NEAR(c, 1000.0 / parts, 2.0) << parts << " parts";
  }
}

// A heavy cluster (the impact region's contacts) is cut finer: the parts balance weight, and
// the cluster's points end up in more than one part.
TEST(RecursiveBisection, AHeavyClusterIsSharedByWeightNotByCount) {
  std::vector<Vec<2>> x = random_points<2>(900, 5);
  std::vector<double> w(x.size(), 1.0);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(4.0, 5.0);
  for (int k = 0; k < 100; ++k) {
    x.push_back(Vec<2>(u(rng), u(rng)));
    w.push_back(20.0);
  }
  const int parts = 4;
  const RecursiveBisection<2> rcb(x, w, parts);
  EXPECT_LT(imbalance(rcb.part(), w, parts), 1.0 + 2.0 * 20.0 / (2900.0 / parts));
  std::vector<bool> holds_cluster(parts, false);
  for (std::size_t i = 900; i < x.size(); ++i) holds_cluster[rcb.part()[i]] = true;
  EXPECT_GE(std::count(holds_cluster.begin(), holds_cluster.end(), true), 2);
  // By count the shares are far from equal: the cluster's parts hold few points.
  std::vector<int> count(parts, 0);
  for (int p : rcb.part()) ++count[p];
  EXPECT_GT(*std::max_element(count.begin(), count.end()),
            2 * *std::min_element(count.begin(), count.end()));
}

// Two parts of a long strip are cut across its length: every point of the lower part lies
// left of every point of the upper one.
TEST(RecursiveBisection, CutsAcrossTheLongestSide) {
  std::vector<Vec<3>> x = random_points<3>(400, 13);
  for (Vec<3>& p : x) p.y() *= 0.1, p.z() *= 0.1, p.x() *= 3.0;
  const std::vector<double> w(x.size(), 1.0);
  const RecursiveBisection<3> rcb(x, w, 2);
  double lower_right = -1e9, upper_left = 1e9;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (rcb.part()[i] == 0)
      lower_right = std::max(lower_right, x[i].x());
    else
      upper_left = std::min(upper_left, x[i].x());
  EXPECT_LT(lower_right, upper_left);
}

// Points at one position cannot be cut apart: the first part holds them, the others none.
TEST(RecursiveBisection, CoincidentPointsStayInOnePart) {
  const std::vector<Vec<2>> x(10, Vec<2>(1.0, 2.0));
  const std::vector<double> w(x.size(), 1.0);
  const RecursiveBisection<2> rcb(x, w, 3);
  for (int p : rcb.part()) EXPECT_EQ(p, 0);
  EXPECT_EQ(rcb.part_of(Vec<2>(1.0, 2.0)), 0);
  EXPECT_DOUBLE_EQ(imbalance(rcb.part(), w, 3), 3.0);
}

// Ghosts: for every pair closer than the reach whose grains lie in different parts, each grain's
// near parts include the other's part; its own part is always near, and a point far from
// every cut is near its own part alone.
TEST(RecursiveBisection, PartsNearAGrainHoldEveryPartnerWithinReach) {
  const std::vector<Vec<3>> x = random_points<3>(1500, 17);
  const std::vector<double> w(x.size(), 1.0);
  const double reach = 0.9;
  for (int parts : {2, 3, 6}) {
    const RecursiveBisection<3> rcb(x, w, parts);
    std::vector<std::vector<int>> near(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      rcb.for_each_part_near(x[i], reach, [&](int part) { near[i].push_back(part); });
      EXPECT_TRUE(std::is_sorted(near[i].begin(), near[i].end()));
      EXPECT_NE(std::find(near[i].begin(), near[i].end(), rcb.part()[i]), near[i].end());
    }
    std::size_t crossing = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
      for (std::size_t j = i + 1; j < x.size(); ++j) {
        if ((x[i] - x[j]).norm() >= reach || rcb.part()[i] == rcb.part()[j]) continue;
        ++crossing;
        EXPECT_NE(std::find(near[i].begin(), near[i].end(), rcb.part()[j]), near[i].end());
        EXPECT_NE(std::find(near[j].begin(), near[j].end(), rcb.part()[i]), near[j].end());
      }
    EXPECT_GT(crossing, 0u) << parts << " parts";  // the test has pairs across cuts to check
  }
  // Two parts of a strip cut near x = 0: a point at x = -4 is near its own part alone.
  std::vector<Vec<2>> strip;
  for (int k = -50; k < 50; ++k) strip.push_back(Vec<2>(0.1 * k + 0.05, 0.0));
  const RecursiveBisection<2> halves(strip, std::vector<double>(strip.size(), 1.0), 2);
  std::vector<int> near;
  halves.for_each_part_near(Vec<2>(-4.0, 0.0), 1.0, [&](int part) { near.push_back(part); });
  EXPECT_EQ(near, std::vector<int>{0});
  near.clear();
  halves.for_each_part_near(Vec<2>(-0.5, 0.0), 1.0, [&](int part) { near.push_back(part); });
  EXPECT_EQ(near, (std::vector<int>{0, 1}));
}

// One descent gives a point's part and the other parts near it, as part_of and
// for_each_part_near do: for random points, and for a lattice whose cuts and reaches are whole
// numbers, where points lie exactly a reach from a cut.
TEST(RecursiveBisection, OnePlacementGivesThePartAndTheOtherPartsNear) {
  std::size_t alone = 0, beside_others = 0;  // the points of each kind checked
  const auto expect_as_search = [&](const RecursiveBisection<3>& rcb, const std::vector<Vec<3>>& at,
                                    double reach) {
    for (const Vec<3>& p : at) {
      std::vector<int> searched, placed;
      const int own = rcb.part_of(p);
      rcb.for_each_part_near(p, reach, [&](int part) {
        if (part != own) searched.push_back(part);
      });
      EXPECT_EQ(rcb.part_and_others_near(p, reach, [&](int part) { placed.push_back(part); }), own);
      EXPECT_EQ(placed, searched) << rcb.parts() << " parts, reach " << reach;
      (searched.empty() ? alone : beside_others) += 1;
    }
  };
  const std::vector<Vec<3>> x = random_points<3>(2000, 23);
  std::vector<Vec<3>> lattice;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) lattice.push_back(Vec<3>(i, j, k));
  for (int parts : {2, 3, 6, 16}) {
    const RecursiveBisection<3> random(x, std::vector<double>(x.size(), 1.0), parts);
    expect_as_search(random, random_points<3>(3000, 29), 0.9);
    const RecursiveBisection<3> layers(lattice, std::vector<double>(lattice.size(), 1.0), parts);
    for (double reach : {1.0, 2.0}) expect_as_search(layers, lattice, reach);
  }
  EXPECT_GT(alone, 1000u);
  EXPECT_GT(beside_others, 1000u);
}

// The build over ranks: every point in the part of its position, no part empty, and each part
// within a point's weight of its share per cut (its cuts fall on histogram edges, not between
// points, so they come within side / 64^4 of the share).
TEST(RecursiveBisection, OverRanksBalancesWeightAndPlacesEveryPoint) {
  const std::vector<Vec<3>> x = random_points<3>(2000, 7);
  const std::vector<double> w = random_weights(x.size(), 11);
  double total = 0.0;
  for (double value : w) total += value;
  for (int parts = 1; parts <= 7; ++parts) {
    const auto rcb = RecursiveBisection<3>::over_ranks(RankTeam(), x, w, parts);
    expect_every_point_in_the_part_of_its_position(rcb, x);
    // At most 3 levels of cuts, each missing by at most the heaviest point (3.0).
    EXPECT_LT(imbalance(rcb.part(), w, parts), 1.0 + 3 * 3.0 / (total / parts)) << parts;
  }
}

// A jet's lattice: layers of points that share their coordinate bit for bit, and a heavy
// cluster. The cuts fall between layers and share the weight as the build on one process does,
// within a layer's weight.
TEST(RecursiveBisection, OverRanksCutsALatticeBetweenItsLayers) {
  std::vector<Vec<3>> x;
  std::vector<double> w;
  for (int layer = 0; layer < 60; ++layer)
    for (int k = 0; k < 50; ++k) {
      x.push_back(Vec<3>(0.1 * (k % 7), 0.1 * (k / 7), 1.0 * layer));
      w.push_back(layer < 10 ? 8.0 : 1.0);  // the impact's end is heavy
    }
  double total = 0.0;
  for (double value : w) total += value;
  for (int parts : {2, 3, 4, 8}) {
    const auto rcb = RecursiveBisection<3>::over_ranks(RankTeam(), x, w, parts);
    for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(rcb.part_of(x[i]), rcb.part()[i]);
    const double layer_weight = 50 * 8.0;
    EXPECT_LT(imbalance(rcb.part(), w, parts), 1.0 + 3 * layer_weight / (total / parts))
        << parts << " parts";
    const RecursiveBisection<3> serial(x, w, parts);
    EXPECT_NEAR(imbalance(rcb.part(), w, parts), imbalance(serial.part(), w, parts),
                3 * layer_weight / (total / parts))
        << parts << " parts";
  }
}

TEST(RecursiveBisection, OverRanksKeepsCoincidentPointsTogether) {
  const std::vector<Vec<2>> x(10, Vec<2>(1.0, 2.0));
  const std::vector<double> w(x.size(), 1.0);
  const auto rcb = RecursiveBisection<2>::over_ranks(RankTeam(), x, w, 3);
  for (int p : rcb.part()) EXPECT_EQ(p, 0);
  EXPECT_EQ(rcb.part_of(Vec<2>(1.0, 2.0)), 0);
  const auto none = RecursiveBisection<2>::over_ranks(RankTeam(), std::vector<Vec<2>>{},
                                                      std::vector<double>{}, 4);
  EXPECT_EQ(none.part_of(Vec<2>(0.0, 0.0)), 0);
  EXPECT_THROW(RecursiveBisection<2>::over_ranks(RankTeam(), x, std::vector<double>(3), 2),
               std::invalid_argument);
}

// The number of distinct parts a line of positions along `axis` through p crosses.
template <int D>
int parts_along(const RecursiveBisection<D>& rcb, Vec<D> p, int axis) {
  std::vector<int> seen;
  for (int k = -60; k <= 60; ++k) {
    p[axis] = 0.5 * k;
    seen.push_back(rcb.part_of(p));
  }
  std::sort(seen.begin(), seen.end());
  return static_cast<int>(std::unique(seen.begin(), seen.end()) - seen.begin());
}

// A tall column (z its longest side, as a jet's): with no lengthwise levels the first cut is
// across z; with lengthwise levels along z, 2^levels parts share every height, each line along
// z crossing only the parts of the deeper levels' cuts; the build over ranks agrees.
TEST(RecursiveBisection, LengthwiseLevelsCutAlongTheAxis) {
  std::vector<Vec<3>> x = random_points<3>(3000, 19);
  for (Vec<3>& p : x) p.z() *= 6.0;
  const std::vector<double> w = random_weights(x.size(), 23);
  const Vec<3> inside(1.0, -2.0, 0.0);
  EXPECT_EQ(parts_along(RecursiveBisection<3>(x, w, 2), inside, 2), 2);
  for (int levels : {1, 2}) {
    const LengthwiseCuts lengthwise{2, levels};
    for (int parts : {2, 4, 8}) {
      const RecursiveBisection<3> rcb(x, w, parts, lengthwise);
      expect_every_point_in_the_part_of_its_position(rcb, x);
      const int crossed =
          parts >> std::min(levels, static_cast<int>(std::bit_width(unsigned(parts))) - 1);
      for (const Vec<3>& p : {inside, Vec<3>(-3.0, 4.0, 0.0), Vec<3>(4.5, 4.5, 0.0)})
        EXPECT_EQ(parts_along(rcb, p, 2), crossed) << levels << " levels, " << parts << " parts";
      const auto over = RecursiveBisection<3>::over_ranks(RankTeam(), x, w, parts, lengthwise);
      expect_every_point_in_the_part_of_its_position(over, x);
      for (const Vec<3>& p : {inside, Vec<3>(-3.0, 4.0, 0.0), Vec<3>(4.5, 4.5, 0.0)})
        EXPECT_EQ(parts_along(over, p, 2), crossed) << levels << " levels, " << parts << " parts";
    }
  }
}

// Points that share their coordinates across the axis (a line along it) cannot be cut
// lengthwise: the cut falls across the axis, and no part is left empty.
TEST(RecursiveBisection, ALineAlongTheLengthwiseAxisIsCutAcrossIt) {
  std::vector<Vec<2>> x;
  for (int k = 0; k < 40; ++k) x.push_back(Vec<2>(0.25 * k, 3.0));
  const std::vector<double> w(x.size(), 1.0);
  const LengthwiseCuts lengthwise{0, 2};
  const RecursiveBisection<2> rcb(x, w, 4, lengthwise);
  expect_every_point_in_the_part_of_its_position(rcb, x);
  const auto over = RecursiveBisection<2>::over_ranks(RankTeam(), x, w, 4, lengthwise);
  expect_every_point_in_the_part_of_its_position(over, x);
  EXPECT_THROW(RecursiveBisection<2>(x, w, 2, LengthwiseCuts{2, 1}), std::invalid_argument);
}

TEST(RecursiveBisection, ImbalanceIsTheHeaviestPartOverTheMean) {
  const std::vector<int> part = {0, 0, 1};
  const std::vector<double> w = {1.0, 1.0, 4.0};
  EXPECT_DOUBLE_EQ(imbalance(part, w, 2), 4.0 / 3.0);
  EXPECT_THROW(RecursiveBisection<2>(std::vector<Vec<2>>(2), w, 2), std::invalid_argument);
  EXPECT_THROW(RecursiveBisection<2>(std::vector<Vec<2>>(3), w, 0), std::invalid_argument);
}

}  // namespace
}  // namespace granjet
