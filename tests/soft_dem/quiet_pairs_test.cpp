// QuietPairs skips exactly the pairs of trusted quiet grains that stay apart, its
// classification ends when a trusted grain is pushed, and a rebuild keeps the trusted grains
// until then.
#include "soft_dem/quiet_pairs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <stdexcept>
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
    list();
  }

  // A neighbour rebuild's cell sort and pair list; the trusted grains, while their trust
  // holds, follow the sort as the simulator has them follow it.
  void list() {
    CellGrid<3> grid;
    grid.build(p.position(), 1.4);
    p.gather(grid.order());
    quiet.gather(grid.order());
    build_half_pairs<3>(
        grid, p.position(), p.radius(), 0.4, [](auto, auto) { return false; }, pairs);
    pair_row.clear();
    for (std::uint32_t i = 0; i + 1 < pairs.first.size(); ++i)
      for (std::uint32_t k = pairs.first[i]; k < pairs.first[i + 1]; ++k) pair_row.push_back(i);
    force_before.assign(p.size(), Vec<3>::Zero());
  }
  // Every grain flies on for `passes` steps of the integrator, with no force.
  void coast(int passes) {
    for (int pass = 0; pass < passes; ++pass)
      for (std::size_t i = 0; i < p.size(); ++i)
        p.position()[i] += kHalfStep * (p.velocity()[i] + p.velocity()[i]);
  }

  void classify(std::span<const std::uint8_t> owned = {}) {
    quiet.classify(p, force_before, pairs, pair_row, OpenSpace<3>{}, 2 * kHalfStep, reach, owned);
  }
  void relist(std::span<const std::uint8_t> owned = {}) {
    quiet.relist(p, pairs, pair_row, OpenSpace<3>{}, 2 * kHalfStep, reach, owned);
  }
  // The grains (ids) of the tested pairs, the lower first, in order (a rebuild may list a pair
  // either way round).
  std::vector<std::pair<GrainId, GrainId>> tested() const {
    std::vector<std::pair<GrainId, GrainId>> out;
    for (std::uint32_t k : quiet.tested())
      out.emplace_back(std::minmax(p.id()[pair_row[k]], p.id()[pairs.partner[k]]));
    std::sort(out.begin(), out.end());
    return out;
  }

  static constexpr double kHalfStep = 0.001;
  static constexpr auto reach = [](std::uint32_t, std::uint32_t) { return 1.0; };
  Particles<3> p;
  PairList pairs;
  std::vector<std::uint32_t> pair_row;
  std::vector<Vec<3>> force_before;
  QuietPairs<3> quiet;
};

using Pairs = std::vector<std::pair<GrainId, GrainId>>;

// What the simulator does after a pass, on one thread: the look at every grain, then the ageing.
void end_pass(QuietPairs<3>& quiet, const std::vector<std::uint8_t>& forced) {
  quiet.after_pass(quiet.trusted_pushed(forced, 0, forced.size()));
}

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
// moves the grains most, the skipped pairs stay apart for every pass the listing serves.
void expect_skipped_pairs_stay_apart(Row& row) {
  std::vector<bool> skipped(row.pairs.size(), true);
  for (std::uint32_t k : row.quiet.tested()) skipped[k] = false;
  ASSERT_GT(std::count(skipped.begin(), skipped.end(), true), 10);
  for (int pass = 0; pass < QuietPairs<3>::kMaxAge; ++pass) {
    for (std::size_t k = 0; k < row.pairs.size(); ++k) {
      if (!skipped[k]) continue;
      const Vec<3> r = row.p.position()[row.pair_row[k]] - row.p.position()[row.pairs.partner[k]];
      ASSERT_GE(r.squaredNorm(), 1.0) << "pair " << k << " at pass " << pass;
    }
    row.coast(1);
  }
}

TEST(QuietPairs, SkippedPairsStayApartWhileTheGrainsCoast) {
  Row row(20, 1e-9, 3.0e3);
  row.classify();
  expect_skipped_pairs_stay_apart(row);
}

// A rebuild keeps the trusted grains while no trusted grain was pushed: the new list's pairs
// are tested again from the positions of then, and serve kMaxAge passes from there.
TEST(QuietPairs, SkippedPairsStayApartAfterARebuildThatKeptTheTrustedGrains) {
  Row row(20, 1e-9, 3.0e3);
  row.classify();
  const std::vector<std::uint8_t> forced(row.p.size(), 0);
  for (int pass = 0; pass < 100; ++pass) end_pass(row.quiet, forced);
  row.coast(100);
  ASSERT_TRUE(row.quiet.trust_holds());
  row.list();
  row.relist();
  expect_skipped_pairs_stay_apart(row);
}

// The grains reversed (as a removal or a move to the owners leaves them in no order) and sorted
// again by the rebuild, in the cells of a row mirrored about x = 0, whose order runs the other
// way: each grain's mark goes with it through both.
TEST(QuietPairs, TheTrustedGrainsGoWithTheGrainsThroughARebuild) {
  Row row(20);
  row.classify();
  const std::vector<std::uint8_t> forced(row.p.size(), 0);
  for (int pass = 0; pass + 1 < QuietPairs<3>::kMaxAge; ++pass) end_pass(row.quiet, forced);
  row.coast(QuietPairs<3>::kMaxAge - 1);
  std::vector<std::uint32_t> reversed(row.p.size());
  for (std::uint32_t k = 0; k < reversed.size(); ++k) reversed[k] = row.p.size() - 1 - k;
  row.p.gather(reversed);
  row.quiet.gather(reversed);
  for (Vec<3>& x : row.p.position()) x.x() = -x.x();
  row.list();
  ASSERT_EQ(row.p.id()[0], 19);
  row.relist();
  EXPECT_EQ(row.tested(), (Pairs{{0, 1}, {1, 2}, {2, 3}, {3, 4}}));
  // A listing for kMaxAge passes from the rebuild on, however old the classification.
  for (int pass = 0; pass + 1 < QuietPairs<3>::kMaxAge; ++pass) end_pass(row.quiet, forced);
  EXPECT_TRUE(row.quiet.fresh());
  end_pass(row.quiet, forced);
  EXPECT_FALSE(row.quiet.fresh());
  EXPECT_TRUE(row.quiet.trust_holds());  // the grains are still quiet: a rebuild may keep them
}

// Over MPI ranks a rebuild moves grains between ranks: one that arrives from another rank is
// not trusted here, nor is one that stays here as a ghost.
TEST(QuietPairs, AGrainThatArrivesOrBecomesAGhostIsNotTrusted) {
  Row row(20);
  row.classify();
  std::vector<std::uint32_t> keep;  // all but grain 10, which leaves and comes back
  for (std::uint32_t i = 0; i < row.p.size(); ++i)
    if (row.p.id()[i] != 10) keep.push_back(i);
  const std::size_t grains = row.p.size();
  const Particles<3>::Moves moves = Particles<3>::compaction(keep);
  row.p.compact(moves, keep.size(), 1);
  row.quiet.compact(moves, keep.size(), 1);
  row.p.add(10, GrainKind::kFree, Vec<3>(10 * (1.0 + 1e-9), 0.0, 0.0), Vec<3>(0.0, 0.0, -1.0), 0.5,
            1.0);
  ASSERT_EQ(row.p.size(), grains);
  row.list();
  std::vector<std::uint8_t> owned(row.p.size(), 1);
  for (std::size_t i = 0; i < row.p.size(); ++i)
    if (row.p.id()[i] == 19) owned[i] = 0;
  row.relist(owned);
  EXPECT_EQ(row.tested(), (Pairs{{0, 1}, {1, 2}, {2, 3}, {3, 4}, {9, 10}, {10, 11}, {18, 19}}));
}

// Once a trusted grain is pushed its mark no longer says it is quiet: a rebuild keeps nothing,
// and a relisting is refused.
TEST(QuietPairs, ATrustedGrainPushedEndsTheTrustAndARelistingIsRefused) {
  Row row(20);
  row.classify();
  std::vector<std::uint8_t> forced(row.p.size(), 0);
  forced[12] = 1;
  end_pass(row.quiet, forced);
  EXPECT_FALSE(row.quiet.trust_holds());
  row.list();
  EXPECT_THROW(row.relist(), std::logic_error);
  row.classify();
  EXPECT_TRUE(row.quiet.trust_holds());
  row.quiet.expire();
  EXPECT_FALSE(row.quiet.trust_holds());
}

}  // namespace
}  // namespace granjet::dem
