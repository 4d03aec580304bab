// The cells of the neighbour lists' centres (event_driven/centre_grid.hpp): a gather finds
// exactly the centres within the shell at their nearest images, in 2D and 3D, after inserts,
// removals (the back-indices), moves across the box and cells outgrowing their room.
#include "event_driven/centre_grid.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/random.hpp"

namespace granjet::ed {
namespace {

template <class T>
class CentreGridGather : public ::testing::Test {};
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(CentreGridGather, Dims);

constexpr double kShell = 1.6;

template <int D>
Vec<D> random_point(const Vec<D>& box, Random& rng) {
  Vec<D> x;
  for (int a = 0; a < D; ++a) x[a] = box[a] * rng.uniform();
  return x;
}

// The grains in the grid whose nearest image lies within kShell (r + r_k) of x.
template <int D>
std::multiset<std::uint32_t> within(const Vec<D>& x, double r, const std::vector<Vec<D>>& at,
                                    const std::vector<double>& radius, const std::vector<bool>& in,
                                    const PeriodicBox<D>& space) {
  std::multiset<std::uint32_t> out;
  for (std::uint32_t k = 0; k < at.size(); ++k)
    if (in[k] && space.separation(at[k], x).norm() < kShell * (r + radius[k])) out.insert(k);
  return out;
}

template <int D>
std::multiset<std::uint32_t> gathered(const CentreGrid<D>& grid, const Vec<D>& x, double r,
                                      std::vector<std::uint32_t>& scratch) {
  const std::size_t n = grid.gather_within(x, r, kShell, scratch);
  return {scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(n)};
}

TYPED_TEST(CentreGridGather, FindsTheCentresWithinTheShellAfterInsertsRemovalsAndWidening) {
  constexpr int D = TypeParam::kDim;
  const Vec<D> box = Vec<D>::LinSpaced(D, 5.0, 6.5);  // 3 and 4 cells per axis (reach 1.6)
  const std::size_t n = D == 3 ? 600 : 200;           // far more than 8 to a cell
  Random rng(5);
  std::vector<Vec<D>> at(n);
  std::vector<double> radius(n);
  std::vector<bool> in(n, true);
  CentreGrid<D> grid(box, kShell * 1.0, n);
  for (std::uint32_t i = 0; i < n; ++i) {
    at[i] = random_point<D>(box, rng);
    radius[i] = 0.3 + 0.2 * rng.uniform();  // largest diameter 1
    grid.insert(i, at[i], radius[i]);
  }
  const PeriodicBox<D> space(box);
  std::vector<std::uint32_t> scratch;
  const auto check = [&] {
    for (int probe = 0; probe < 50; ++probe) {
      const Vec<D> x = random_point<D>(box, rng);
      const double r = 0.3 + 0.2 * rng.uniform();
      ASSERT_EQ(gathered<D>(grid, x, r, scratch), within<D>(x, r, at, radius, in, space));
    }
    for (std::uint32_t i = 0; i < n; ++i)
      if (in[i]) {
        ASSERT_EQ(grid.centre(i), at[i]);
        ASSERT_EQ(grid.radius(i), radius[i]);
      }
  };
  check();
  // Grains leave (some for good) and come back elsewhere, across the box's faces too.
  for (int round = 0; round < 2000; ++round) {
    const auto i = static_cast<std::uint32_t>(rng.below(n));
    if (in[i]) {
      grid.remove(i);
      in[i] = false;
    }
    if (round % 7 != 0) {
      at[i] = random_point<D>(box, rng);
      grid.insert(i, at[i], radius[i]);
      in[i] = true;
    }
  }
  check();
  grid.clear();
  std::fill(in.begin(), in.end(), false);
  check();
}

}  // namespace
}  // namespace granjet::ed
