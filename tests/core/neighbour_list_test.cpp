// The cell-grid half list finds exactly the pairs a brute-force search finds (in open space in
// its order too); the cell sort and the parallel sort give one order for any thread count.
#include "core/neighbour_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <numeric>
#include <random>
#include <set>

#include "core/parallel_sort.hpp"

namespace granjet {
namespace {

template <class T>
class NeighbourList : public ::testing::Test {};
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(NeighbourList, Dims);

TYPED_TEST(NeighbourList, HalfListMatchesBruteForce) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 12.0);
  std::vector<Vec<D>> x(600);
  std::vector<double> radius(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int d = 0; d < D; ++d) x[i][d] = u(rng);
    radius[i] = i % 2 ? 0.5 : 0.4;
  }
  x.back() *= 40.0;  // one far grain stretches the box
  const double skin = 0.3;
  CellGrid<D> grid;
  grid.build(x, 1.0 + skin);
  std::vector<Vec<D>> sorted;
  std::vector<double> sorted_r;
  for (std::uint32_t k : grid.order()) {
    sorted.push_back(x[k]);
    sorted_r.push_back(radius[k]);
  }
  PairList list;
  build_half_pairs<D>(
      grid, sorted, sorted_r, skin, [](auto, auto) { return false; }, list);
  // Entry for entry, in the brute force's order (each row's partners ascending): the list
  // depends on the grains' order and positions alone, not on how the cells are walked.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> found, expected;
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t k = list.first[i]; k < list.first[i + 1]; ++k)
      found.emplace_back(i, list.partner[k]);
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t j = i + 1; j < sorted.size(); ++j) {
      const double cut = sorted_r[i] + sorted_r[j] + skin;
      if ((sorted[i] - sorted[j]).squaredNorm() < cut * cut) expected.emplace_back(i, j);
    }
  EXPECT_GT(expected.size(), 100u);
  EXPECT_EQ(found, expected);
}

// Across a periodic box the list holds every minimum-image pair once, still with i < j (the
// soft DEM's fused force pass relies on it), also for pairs found across the wrap.
TYPED_TEST(NeighbourList, PeriodicHalfListMatchesMinimumImageBruteForce) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(11);
  const PeriodicBox<D> space(Vec<D>::Constant(7.0));
  std::uniform_real_distribution<double> u(0.0, 7.0);
  std::vector<Vec<D>> x(D == 2 ? 60 : 250);
  for (Vec<D>& xi : x)
    for (int d = 0; d < D; ++d) xi[d] = u(rng);
  const std::vector<double> radius(x.size(), 0.5);
  const double skin = 0.3;
  CellGrid<D> grid;
  grid.build_periodic(x, space.box, 1.0 + skin);
  std::vector<Vec<D>> sorted;
  for (std::uint32_t k : grid.order()) sorted.push_back(x[k]);
  PairList list;
  build_half_pairs<D>(
      grid, sorted, radius, skin, [](auto, auto) { return false; }, list, space);
  std::multiset<std::pair<std::uint32_t, std::uint32_t>> found;
  std::set<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t k = list.first[i]; k < list.first[i + 1]; ++k) {
      ASSERT_GT(list.partner[k], i);
      found.insert({i, list.partner[k]});
    }
  std::size_t across = 0;
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t j = i + 1; j < sorted.size(); ++j) {
      if (space.separation(sorted[i], sorted[j]).norm() >= 1.0 + skin) continue;
      expected.insert({i, j});
      across += (sorted[i] - sorted[j]).norm() >= 1.0 + skin;
    }
  EXPECT_GT(across, 5u);
  EXPECT_EQ(found, std::multiset(expected.begin(), expected.end()));  // no pair twice
}

TEST(PeriodicBox, MinimumImageAndWrap) {
  const PeriodicBox<2> box(Vec<2>(10.0, 4.0));
  EXPECT_TRUE(box.separation(Vec<2>(9.5, 0.5), Vec<2>(0.5, 3.5)).isApprox(Vec<2>(-1.0, 1.0)));
  Vec<2> x(-0.25, 9.0);
  box.wrap(x);
  EXPECT_TRUE(x.isApprox(Vec<2>(9.75, 1.0)));
  Vec<2> tiny(-1e-18, 0.0);  // would round to the box edge itself
  box.wrap(tiny);
  EXPECT_GE(tiny[0], 0.0);
  EXPECT_LT(tiny[0], 10.0);
}

// Scanning runs of cells on several threads and joining them gives the one-thread list entry for
// entry (open space, and periodic with its late pairs).
TYPED_TEST(NeighbourList, ThreadedBuildEqualsSerialBuild) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 9.0);
  std::vector<Vec<D>> x(D == 2 ? 150 : 500);
  for (Vec<D>& xi : x)
    for (int d = 0; d < D; ++d) xi[d] = u(rng);
  const std::vector<double> radius(x.size(), 0.5);
  const PeriodicBox<D> space(Vec<D>::Constant(9.0));
  const auto none = [](auto, auto) { return false; };
  for (bool periodic : {false, true}) {
    CellGrid<D> grid;
    if (periodic)
      grid.build_periodic(x, space.box, 1.3);
    else
      grid.build(x, 1.3);
    std::vector<Vec<D>> sorted;
    for (std::uint32_t k : grid.order()) sorted.push_back(x[k]);
    PairList one, three;
    if (periodic) {
      build_half_pairs<D>(grid, sorted, radius, 0.3, none, one, space, 1);
      build_half_pairs<D>(grid, sorted, radius, 0.3, none, three, space, 3);
    } else {
      build_half_pairs<D>(grid, sorted, radius, 0.3, none, one, OpenSpace<D>{}, 1);
      build_half_pairs<D>(grid, sorted, radius, 0.3, none, three, OpenSpace<D>{}, 3);
    }
    EXPECT_GT(one.size(), 100u);
    EXPECT_EQ(one.first, three.first) << "periodic " << periodic;
    EXPECT_EQ(one.partner, three.partner) << "periodic " << periodic;
  }
}

// With one radius for all grains the build that reads no radius per candidate gives the list of
// the build that does, entry for entry, exclusions kept (open space and periodic, 1 and 3
// threads). Grains on a lattice of spacing 1 put many pairs right at 2 R, where a cut-off
// computed otherwise than R + R + skin would drop or keep pairs of its own.
TYPED_TEST(NeighbourList, UniformRadiusBuildEqualsThePerGrainBuild) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 8.0);
  std::vector<Vec<D>> x;
  for (int k = 0; k < (D == 2 ? 64 : 512); ++k) {  // a lattice, then scattered grains
    Vec<D> p;
    for (int d = 0, rest = k; d < D; ++d, rest /= 8) p[d] = 0.5 + rest % 8;
    x.push_back(p);
  }
  for (int k = 0; k < 200; ++k) {
    Vec<D> p;
    for (int d = 0; d < D; ++d) p[d] = u(rng);
    x.push_back(p);
  }
  const std::vector<double> radius(x.size(), 0.35);
  const double skin = 0.3;  // cut-off 1.0: the lattice's neighbours lie on it
  const auto odd_pairs = [](std::uint32_t i, std::uint32_t j) { return (i & j & 1) != 0; };
  const PeriodicBox<D> space(Vec<D>::Constant(8.0));
  for (bool periodic : {false, true})
    for (int threads : {1, 3}) {
      CellGrid<D> grid;
      if (periodic)
        grid.build_periodic(x, space.box, 2 * radius[0] + skin);
      else
        grid.build(x, 2 * radius[0] + skin);
      std::vector<Vec<D>> sorted;
      for (std::uint32_t k : grid.order()) sorted.push_back(x[k]);
      PairList per_grain, uniform;
      if (periodic) {
        build_half_pairs<D>(grid, sorted, radius, skin, odd_pairs, per_grain, space, threads);
        build_half_pairs<D, true>(grid, sorted, radius, skin, odd_pairs, uniform, space, threads);
      } else {
        build_half_pairs<D>(grid, sorted, radius, skin, odd_pairs, per_grain, OpenSpace<D>{},
                            threads);
        build_half_pairs<D, true>(grid, sorted, radius, skin, odd_pairs, uniform, OpenSpace<D>{},
                                  threads);
      }
      EXPECT_GT(per_grain.size(), 100u);
      EXPECT_EQ(per_grain.first, uniform.first) << "periodic " << periodic << ", " << threads;
      EXPECT_EQ(per_grain.partner, uniform.partner) << "periodic " << periodic << ", " << threads;
    }
}

}  // namespace
}  // namespace granjet

namespace granjet {
namespace {

// The cell sort shared among threads is the one-thread counting sort, entry for entry: grains
// in cell order, index order within a cell, whichever way the threads' runs of cells fall
// (here shuffled grains, so that the runs split them unevenly).
TYPED_TEST(NeighbourList, CellSortIsTheSameForAnyThreadCount) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 9.0);
  std::vector<Vec<D>> x(3000);
  for (Vec<D>& xi : x)
    for (int d = 0; d < D; ++d) xi[d] = u(rng);
  CellGrid<D> one;
  one.build(x, 1.2);
  std::vector<std::uint32_t> start;
  for (std::size_t c = 0; c <= one.cells(); ++c) start.push_back(one.start(c));
  for (int threads : {2, 3, 7}) {
    CellGrid<D> shared;
    shared.build(x, 1.2, threads);
    ASSERT_EQ(shared.cells(), one.cells());
    EXPECT_TRUE(std::ranges::equal(shared.order(), one.order())) << threads << " threads";
    for (std::size_t c = 0; c <= one.cells(); ++c) ASSERT_EQ(shared.start(c), start[c]);
  }
  // Cell order, and index order within a cell.
  for (std::size_t c = 0; c < one.cells(); ++c)
    for (std::uint32_t k = one.start(c); k + 1 < one.start(c + 1); ++k)
      EXPECT_LT(one.order()[k], one.order()[k + 1]);
}

// With ids, a cell's grains come in id order, so that the order is a function of positions and
// ids alone: the same grains given in another order come out in the same order of ids.
TYPED_TEST(NeighbourList, CellSortWithIdsDependsOnPositionsAndIdsAlone) {
  constexpr int D = TypeParam::kDim;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0.0, 6.0);
  const std::size_t n = 2000;
  std::vector<Vec<D>> x(n);
  for (Vec<D>& xi : x)
    for (int d = 0; d < D; ++d) xi[d] = u(rng);
  std::vector<std::int64_t> id(n);
  std::iota(id.begin(), id.end(), 100);
  std::shuffle(id.begin(), id.end(), rng);  // ids not in index order
  // The ids in the order a grid of these grains, given in this order, sorts them.
  const auto sorted_ids = [](const std::vector<Vec<D>>& xs, const std::vector<std::int64_t>& ids,
                             int threads) {
    CellGrid<D> grid;
    grid.build(xs, 1.5, threads, ids);
    std::vector<std::int64_t> out;
    for (std::uint32_t i : grid.order()) out.push_back(ids[i]);
    return out;
  };
  const std::vector<std::int64_t> whole = sorted_ids(x, id, 1);
  EXPECT_EQ(sorted_ids(x, id, 3), whole);
  // The same grains in reverse: the same order of ids.
  EXPECT_EQ(sorted_ids({x.rbegin(), x.rend()}, {id.rbegin(), id.rend()}, 2), whole);
  // Within each cell, increasing ids.
  CellGrid<D> grid;
  grid.build(x, 1.5, 1, id);
  for (std::size_t c = 0; c < grid.cells(); ++c)
    for (std::uint32_t k = grid.start(c); k + 1 < grid.start(c + 1); ++k)
      EXPECT_LT(id[grid.order()[k]], id[grid.order()[k + 1]]);
}

TEST(ParallelSort, GivesStdSortsOrderForAnyThreadCount) {
  std::mt19937_64 rng(3);
  std::vector<std::uint64_t> values(50000);
  for (std::uint64_t& v : values) v = rng();
  std::vector<std::uint64_t> expected = values;
  std::sort(expected.begin(), expected.end());
  for (int threads : {1, 2, 3, 5, 16}) {
    std::vector<std::uint64_t> sorted = values;
    parallel_sort(sorted, std::less<>(), threads);
    EXPECT_EQ(sorted, expected) << threads << " threads";
  }
}

}  // namespace
}  // namespace granjet
