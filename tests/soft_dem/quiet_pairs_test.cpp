// QuietPairs skips exactly the pairs of trusted quiet grains that stay apart, and its
// classification ends when a trusted grain is pushed.
#include "soft_dem/quiet_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <vector>

#include "core/space.hpp"

namespace granjet::dem {
namespace {

// A row of unit grains along x, `gap` apart, all flying at -1 along z but the first, which
// has been slowed by an impact; listed with a skin that keeps only nearest neighbours.
struct Row {
  explicit Row(int grains, double gap = 1e-9, double start = 0.0) {
    for (int k = 0; k < grains; ++k)
      p.add(k, GrainKind::kFree, Vec<3>(start + k * (1.0 + gap), 0.0, 0.0),
            Vec<3>(0.0, 0.0, k == 0 ? -0.5 : -1.0), 0.5, 1.0);
    CellGrid<3> grid;
    grid.build(p.position(), 1.4);
    p.gather(grid.order());
    build_half_pairs<3>(
        grid, p.position(), p.radius(), 0.4, [](auto, auto) { return false; }, pairs);
    for (std::uint32_t i = 0; i + 1 < pairs.first.size(); ++i)
      for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k) pair_row.push_back(i);
    force_before.assign(p.size(), Vec<3>::Zero());
  }

  void classify(std::span<const std::uint8_t> owned = {}) {
    quiet.classify(
        p, force_before, pairs, pair_row, OpenSpace<3>{}, 0.002,
        [](std::uint32_t, std::uint32_t) { return 1.0; }, owned);
  }
  // The grains (ids) of the tested pairs.
  std::vector<std::pair<GrainId, GrainId>> tested() const {
    std::vector<std::pair<GrainId, GrainId>> out;
    for (std::uint32_t k : quiet.tested())
      out.emplace_back(p.id()[pair_row[k]], p.id()[pairs.partner[k]]);
    return out;
  }

  Particles<3> p;
  PairList pairs;
  std::vector<std::uint32_t> pair_row;
  std::vector<Vec<3>> force_before;
  QuietPairs<3> quiet;
};

using Pairs = std::vector<std::pair<GrainId, GrainId>>;

TEST(QuietPairs, SkipsThePairsOfTrustedGrainsOnly) {
  Row row(20);
  ASSERT_EQ(row.pairs.size(), 19u);
  row.classify();
  // Grain 0 moves otherwise; grains 1 .. kMargin are within kMargin pairs of it.
  static_assert(QuietPairs<3>::kMargin == 3);
  EXPECT_EQ(row.tested(), (Pairs{{0, 1}, {1, 2}, {2, 3}, {3, 4}}));
  EXPECT_TRUE(row.quiet.fresh());
}

TEST(QuietPairs, TestsAQuietPairWithinTheDriftOfContact) {
  Row row(20, 1e-15);
  row.classify();
  EXPECT_EQ(row.tested().size(), 19u);
}

// Over MPI ranks a ghost is never trusted, however quiet: its partners beyond the halo are
// not listed on this rank, so the margin around it cannot be known.
TEST(QuietPairs, AGhostIsNotTrustedNorAreTheGrainsWithinTheMarginOfIt) {
  Row row(20);
  std::vector<std::uint8_t> owned(row.p.size(), 1);
  for (std::size_t i = 0; i < row.p.size(); ++i)
    if (row.p.id()[i] == 19) owned[i] = 0;  // the far end of the row is another rank's
  row.classify(owned);
  EXPECT_EQ(row.tested(),
            (Pairs{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {15, 16}, {16, 17}, {17, 18}, {18, 19}}));
}

TEST(QuietPairs, AGrainPushedAtTheLastPassIsNotQuiet) {
  Row row(20);
  row.force_before[10] = Vec<3>(0.0, 0.0, 1e-6);
  row.classify();
  const Pairs tested = row.tested();
  // Its pairs, and those of the grains within kMargin of it.
  for (GrainId a = 6; a < 14; ++a)
    EXPECT_NE(std::find(tested.begin(), tested.end(), std::make_pair(a, a + 1)), tested.end());
  EXPECT_EQ(tested.size(), 4u + 8u);
}

// What the simulator does after a pass, on one thread: the look at every grain, then the ageing.
void end_pass(QuietPairs<3>& quiet, const std::vector<std::uint8_t>& forced) {
  quiet.after_pass(quiet.trusted_pushed(forced, 0, forced.size()));
}

TEST(QuietPairs, ExpiresWhenATrustedGrainIsPushed) {
  Row row(20);
  row.classify();
  std::vector<std::uint8_t> forced(row.p.size(), 0);
  forced[0] = 1;  // not trusted: the classification holds
  end_pass(row.quiet, forced);
  EXPECT_TRUE(row.quiet.fresh());
  forced[15] = 1;
  end_pass(row.quiet, forced);
  EXPECT_FALSE(row.quiet.fresh());
}

TEST(QuietPairs, ExpiresAfterItsLastPassAndAtARebuild) {
  Row row(20);
  row.classify();
  const std::vector<std::uint8_t> forced(row.p.size(), 0);
  for (int pass = 0; pass + 1 < QuietPairs<3>::kMaxAge; ++pass) end_pass(row.quiet, forced);
  EXPECT_TRUE(row.quiet.fresh());
  end_pass(row.quiet, forced);
  EXPECT_FALSE(row.quiet.fresh());
  row.classify();
  row.quiet.expire();
  EXPECT_FALSE(row.quiet.fresh());
}

// The bound holds in the arithmetic the integrator does: far from the origin, where rounding
// moves the grains most, the skipped pairs stay apart for every pass the classification serves.
TEST(QuietPairs, SkippedPairsStayApartWhileTheGrainsCoast) {
  Row row(20, 1e-9, 3.0e3);
  row.classify();
  std::vector<bool> skipped(row.pairs.size(), true);
  for (std::uint32_t k : row.quiet.tested()) skipped[k] = false;
  ASSERT_GT(std::count(skipped.begin(), skipped.end(), true), 10);
  const double half_dt = 0.001;
  for (int pass = 0; pass < QuietPairs<3>::kMaxAge; ++pass) {
    for (std::size_t k = 0; k < row.pairs.size(); ++k) {
      if (!skipped[k]) continue;
      const Vec<3> r = row.p.position()[row.pair_row[k]] - row.p.position()[row.pairs.partner[k]];
      ASSERT_GE(r.squaredNorm(), 1.0) << "pair " << k << " at pass " << pass;
    }
    for (std::size_t i = 0; i < row.p.size(); ++i)
      row.p.position()[i] += half_dt * (row.p.velocity()[i] + row.p.velocity()[i]);
  }
}

}  // namespace
}  // namespace granjet::dem
