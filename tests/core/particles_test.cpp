#include "core/particles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace granjet {
namespace {

// A store of n grains whose id, radius and x-coordinate all equal their index.
Particles<3> numbered(int n) {
  Particles<3> p;
  for (int i = 0; i < n; ++i)
    p.add(i, GrainKind::kFree, Vec<3>(i, 0.0, 0.0), Vec<3>::Zero(), i, 1.0);
  return p;
}

TEST(Particles, CompactionKeepsExactlyTheKeptGrainsAndMovesOnlyThoseBeyondThem) {
  std::mt19937 random(7);
  for (int n : {0, 1, 2, 9, 64}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<std::uint32_t> keep;
      for (int i = 0; i < n; ++i)
        if (std::bernoulli_distribution(0.7)(random)) keep.push_back(static_cast<std::uint32_t>(i));
      const Particles<3>::Moves moves = Particles<3>::compaction(keep);
      // Only the kept grains beyond the first keep.size() places move, each into a place there.
      const auto beyond = std::count_if(keep.begin(), keep.end(),
                                        [&](std::uint32_t i) { return i >= keep.size(); });
      ASSERT_EQ(moves.size(), static_cast<std::size_t>(beyond));
      for (const auto& [from, to] : moves) {
        EXPECT_GE(from, keep.size());
        EXPECT_LT(to, keep.size());
      }
      Particles<3> p = numbered(n);
      const std::size_t room = 5;
      p.compact(moves, keep.size(), room);
      ASSERT_EQ(p.size(), keep.size());
      std::vector<GrainId> ids(p.id().begin(), p.id().end());
      std::sort(ids.begin(), ids.end());
      EXPECT_TRUE(std::equal(ids.begin(), ids.end(), keep.begin(), keep.end()));
      for (std::size_t i = 0; i < p.size(); ++i) {  // each grain's arrays moved together
        EXPECT_EQ(p.radius()[i], static_cast<double>(p.id()[i]));
        EXPECT_EQ(p.position()[i].x(), static_cast<double>(p.id()[i]));
      }
      // The grains kept in place did not move.
      for (std::uint32_t i : keep)
        if (i < keep.size()) {
          EXPECT_EQ(p.id()[i], static_cast<GrainId>(i));
        }
    }
  }
}

TEST(Particles, CompactionLeavesRoomForTheGrainsToBeAdded) {
  Particles<3> p = numbered(10);
  const std::vector<std::uint32_t> keep{1, 4, 8};
  p.compact(Particles<3>::compaction(keep), keep.size(), 20);
  const GrainId* first = p.id().data();
  for (int i = 0; i < 20; ++i)
    p.add(100 + i, GrainKind::kFree, Vec<3>::Zero(), Vec<3>::Zero(), 1.0, 1.0);
  EXPECT_EQ(p.id().data(), first);  // not copied to a longer array
  EXPECT_EQ(p.size(), 23u);
}

}  // namespace
}  // namespace granjet
