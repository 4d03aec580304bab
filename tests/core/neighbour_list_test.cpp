// The cell-grid half list finds exactly the pairs a brute-force search finds.
#include "core/neighbour_list.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

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
  build_half_pairs<D>(grid, sorted, sorted_r, skin, [](auto, auto) { return false; }, list);
  std::set<std::pair<std::uint32_t, std::uint32_t>> found, expected;
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t k = list.first[i]; k < list.first[i + 1]; ++k) {
      ASSERT_GT(list.partner[k], i);
      found.insert({i, list.partner[k]});
    }
  for (std::uint32_t i = 0; i < sorted.size(); ++i)
    for (std::uint32_t j = i + 1; j < sorted.size(); ++j) {
      const double cut = sorted_r[i] + sorted_r[j] + skin;
      if ((sorted[i] - sorted[j]).squaredNorm() < cut * cut) expected.insert({i, j});
    }
  EXPECT_GT(expected.size(), 100u);
  EXPECT_EQ(found, expected);
}

}  // namespace
}  // namespace granjet
