// The event-driven cell list: every pair that can touch is in reach, with the right periodic
// image; faces have hysteresis; the layer scanned after a move is exactly what came into reach.
#include "event_driven/cell_list.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/random.hpp"

namespace granjet::ed {
namespace {

template <class T>
class CellListReach : public ::testing::Test {};
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(CellListReach, Dims);

template <int D>
std::vector<Vec<D>> random_points(const Vec<D>& box, std::size_t n, std::uint64_t seed) {
  Random rng(seed);
  std::vector<Vec<D>> x(n);
  for (Vec<D>& p : x)
    for (int a = 0; a < D; ++a) p[a] = box[a] * rng.uniform();
  return x;
}

// The gathered neighbours other than i as (k -> separation x_k + shift - x_i, the shift zero
// unless the neighbourhood is shifted), each at most once; i itself (gathered with its own
// cell) with no shift.
template <int D>
std::map<std::uint32_t, Vec<D>> reach(std::uint32_t i, const std::vector<Vec<D>>& x,
                                      const typename CellList<D>::Neighbourhood& hood) {
  std::map<std::uint32_t, Vec<D>> out;
  for (std::size_t m = 0; m < hood.size; ++m) {
    const std::uint32_t k = hood.grain[m];
    const Vec<D> shift = hood.shifted ? hood.shift[hood.image[m]] : Vec<D>::Zero();
    if (k == i) {
      EXPECT_EQ(shift, Vec<D>::Zero());
      continue;
    }
    EXPECT_TRUE(out.emplace(k, Vec<D>(x[k] + shift - x[i])).second) << "gathered twice: " << k;
  }
  return out;
}

TYPED_TEST(CellListReach, PeriodicBoxReachesEveryPairCloserThanADiameterAtItsNearestImage) {
  constexpr int D = TypeParam::kDim;
  const Vec<D> box = Vec<D>::LinSpaced(D, 6.3, 7.9);  // 6 and 7 cells per axis
  const auto x = random_points<D>(box, 400, 11);
  auto cells = CellList<D>::periodic(box, 1.0, x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) cells.insert(i, x[i]);
  typename CellList<D>::Neighbourhood hood;
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    cells.gather(i, hood);
    const auto seen = reach<D>(i, x, hood);
    for (std::uint32_t k = 0; k < x.size(); ++k) {
      const Vec<D> nearest = cells.minimum_image(x[k] - x[i]);
      if (k == i || nearest.norm() >= 1.0) continue;
      const auto it = seen.find(k);
      ASSERT_NE(it, seen.end()) << i << " misses " << k;
      EXPECT_LT((it->second - nearest).norm(), 1e-12);
    }
  }
}

TYPED_TEST(CellListReach, OpenCellsReachEveryCloseGrainAlsoOutsideTheCoveredBox) {
  constexpr int D = TypeParam::kDim;
  const Vec<D> box = Vec<D>::Constant(8.0);
  auto x = random_points<D>(box, 300, 5);
  for (Vec<D>& p : x) p = 2.0 * p - Vec<D>::Constant(4.0);  // half of them outside [0, 8)
  auto cells = CellList<D>::open(Vec<D>::Zero(), box, 1.0, x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) cells.insert(i, x[i]);
  typename CellList<D>::Neighbourhood hood;
  for (std::uint32_t i = 0; i < x.size(); ++i) {
    cells.gather(i, hood);
    const auto seen = reach<D>(i, x, hood);
    for (std::uint32_t k = 0; k < x.size(); ++k) {
      if (k != i && (x[k] - x[i]).norm() < 1.0) {
        EXPECT_TRUE(seen.count(k)) << i << " misses " << k;
      }
    }
  }
}

TYPED_TEST(CellListReach, AfterAMoveTheNewLayerIsExactlyWhatCameIntoReach) {
  constexpr int D = TypeParam::kDim;
  const Vec<D> box = Vec<D>::Constant(5.5);  // 5 cells of 1.1: the layer wraps around
  const auto x = random_points<D>(box, 250, 3);
  auto cells = CellList<D>::periodic(box, 1.0, x.size());
  for (std::uint32_t i = 0; i < x.size(); ++i) cells.insert(i, x[i]);
  typename CellList<D>::Neighbourhood hood;
  for (std::uint32_t i = 0; i < 40; ++i) {
    for (int axis = 0; axis < D; ++axis) {
      for (int direction : {-1, 1}) {
        cells.gather(i, hood);
        const auto before = reach<D>(i, x, hood);
        cells.move(i, axis, direction);
        cells.gather(i, hood);
        const auto after = reach<D>(i, x, hood);
        cells.gather_new_layer(i, axis, direction, hood);
        const auto layer = reach<D>(i, x, hood);
        std::set<std::uint32_t> expected;
        for (const auto& [k, dr] : after)
          if (!before.count(k)) expected.insert(k);
        std::set<std::uint32_t> got;
        for (const auto& [k, dr] : layer) got.insert(k);
        EXPECT_EQ(got, expected);
        cells.move(i, axis, -direction);
      }
    }
  }
}

// A crowded cell (the outermost cell of an open grid, where far grains gather): every grain is
// gathered once however many share the cell, also after removals from the middle of its list and
// moves out and back in.
TEST(CellList, CrowdedCellsGatherEveryGrainOnce) {
  constexpr std::uint32_t kGrains = 40;
  auto cells = CellList<3>::open(Vec<3>::Zero(), Vec<3>::Constant(3.3), 1.0, kGrains);
  const Vec<3> corner = Vec<3>::Constant(50.0);  // beyond the box: all in the last cell
  for (std::uint32_t i = 0; i < kGrains; ++i) cells.insert(i, corner);
  std::set<std::uint32_t> present;
  for (std::uint32_t i = 0; i < kGrains; ++i) present.insert(i);
  const auto gathered = [&] {
    CellList<3>::Neighbourhood hood;
    cells.gather(*present.begin(), hood);
    std::multiset<std::uint32_t> got(hood.grain.begin(), hood.grain.begin() + hood.size);
    return got;
  };
  EXPECT_EQ(gathered(), std::multiset<std::uint32_t>(present.begin(), present.end()));
  for (std::uint32_t i : {3u, 0u, 39u, 20u, 8u, 9u, 10u}) {
    cells.remove(i);
    present.erase(i);
    EXPECT_EQ(gathered(), std::multiset<std::uint32_t>(present.begin(), present.end()));
  }
  for (std::uint32_t i = 21; i < 35; ++i) {  // two cells away, out of reach, and back
    cells.move(i, 0, -1);
    cells.move(i, 0, -1);
    present.erase(i);
    EXPECT_EQ(gathered(), std::multiset<std::uint32_t>(present.begin(), present.end()));
  }
  for (std::uint32_t i = 21; i < 35; ++i) {
    cells.move(i, 0, 1);
    cells.move(i, 0, 1);
    present.insert(i);
  }
  EXPECT_EQ(gathered(), std::multiset<std::uint32_t>(present.begin(), present.end()));
}

TEST(CellList, FacesHaveHysteresisAndThePeriodicBoxWraps) {
  // 4 cells of 1.125 for diameter 1: hysteresis (1.125 - 1)/2 = 0.0625 beyond each face.
  auto cells = CellList<2>::periodic(Vec<2>(4.5, 4.5), 1.0, 1);
  cells.insert(0, Vec<2>(4.0, 1.0));  // cell (3, 0)
  auto exit = cells.next_exit(0, Vec<2>(4.0, 1.0), Vec<2>(2.0, 0.0));
  EXPECT_EQ(exit.axis, 0);
  EXPECT_EQ(exit.direction, 1);
  EXPECT_EQ(exit.delay, (4.5625 - 4.0) / 2.0);
  const Vec<2> wrap = cells.move(0, exit.axis, exit.direction);
  EXPECT_EQ(wrap, Vec<2>(-4.5, 0.0));
  // Now at x = 0.0625 in cell (0, 0): turning back, it leaves only at -0.0625.
  exit = cells.next_exit(0, Vec<2>(0.0625, 1.0), Vec<2>(-1.0, 0.0));
  EXPECT_EQ(exit.direction, -1);
  EXPECT_EQ(exit.delay, 0.125);
  EXPECT_EQ(cells.wrap(Vec<2>(-0.0625, 6.0)), Vec<2>(4.4375, 1.5));
}

TEST(CellList, OutermostOpenCellsReachToInfinity) {
  auto cells = CellList<2>::open(Vec<2>(0, 0), Vec<2>(3.3, 3.3), 1.0, 1);
  cells.insert(0, Vec<2>(50.0, 1.5));  // beyond the covered box: the last column
  EXPECT_EQ(cells.next_exit(0, Vec<2>(50.0, 1.5), Vec<2>(1.0, 0.0)).delay, kNever);
  const auto back = cells.next_exit(0, Vec<2>(50.0, 1.5), Vec<2>(-1.0, 0.0));
  EXPECT_EQ(back.direction, -1);
  EXPECT_GT(back.delay, 46.0);
}

}  // namespace
}  // namespace granjet::ed
