// The halo's per-step exchange between the MPI ranks this test was started on (mpirun -n K,
// K = 2..4; main is in decomposition_test.cpp): an owner sends only the states of the ghosts
// that moved otherwise than by coasting, each to its place in the holder's list, and a holder
// whose own pass moved a ghost that its owner did not send is stopped, not left apart from it.
#include "soft_dem/domain.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/rank_team.hpp"

namespace granjet::dem {
namespace {

// A row of grains along x, one diameter apart, cut among the ranks; each rank holds its own and
// the others' within reach of its part (its ghosts).
struct Row {
  static constexpr int kGrains = 40;
  explicit Row(const RankTeam& world) : domain(world, 1.5) {
    std::vector<Vec<3>> mine;
    for (int k = world.rank(); k < kGrains; k += world.size()) mine.push_back(at(k));
    domain.partition(mine, std::vector<double>(mine.size(), 1.0),
                     std::vector<std::uint8_t>(mine.size(), 1));
    for (int k = 0; k < kGrains; ++k) {
      bool ghost = false;
      const int owner =
          domain.owner_and_ghost_ranks(at(k), [&](int r) { ghost = ghost || r == world.rank(); });
      if (owner != world.rank() && !ghost) continue;
      x.push_back(at(k));
      id.push_back(k);
      owned.push_back(owner == world.rank());
    }
    domain.list_halo(x, id, owned);
  }
  static Vec<3> at(int k) { return Vec<3>(k, 0.0, 0.0); }
  std::size_t ghosts() const { return x.size() - std::count(owned.begin(), owned.end(), 1); }

  Domain<3> domain;
  std::vector<Vec<3>> x;
  std::vector<GrainId> id;
  std::vector<std::uint8_t> owned;
};

// Owners send the grains whose id is a multiple of 3, each with its id as its state: the
// holders get exactly those, at their places, and the others keep what they had.
TEST(Domain, OwnersSendOnlyTheStatesOfGhostsThatMovedOtherwise) {
  const RankTeam world = RankTeam::world();
  Row row(world);
  ASSERT_GT(row.ghosts(), 0u);
  std::vector<double> state(row.x.size(), -1.0);
  row.domain.update_ghosts(
      1, [&](std::uint32_t i) { return row.owned[i] && row.id[i] % 3 == 0; },
      [&](std::uint32_t i, double* to) { to[0] = static_cast<double>(row.id[i]); },
      [&](std::uint32_t i, const double* from) { state[i] = from[0]; });
  std::size_t sent_here = 0;
  for (std::size_t i = 0; i < row.x.size(); ++i) {
    if (row.owned[i]) {
      EXPECT_EQ(state[i], -1.0) << "own grain " << row.id[i] << " was overwritten";
    } else if (row.id[i] % 3 == 0) {
      EXPECT_EQ(state[i], static_cast<double>(row.id[i])) << "ghost " << row.id[i];
      ++sent_here;
    } else {
      EXPECT_EQ(state[i], -1.0) << "ghost " << row.id[i] << " was sent though it coasted";
    }
  }
  const Domain<3>::HaloCount& count = row.domain.halo_count();
  EXPECT_EQ(count.exchanges, 1);
  const std::int64_t received = world.sum(static_cast<std::int64_t>(sent_here));
  const std::int64_t sent = world.sum(count.rows_sent), held = world.sum(count.rows_held);
  EXPECT_EQ(received, sent);
  EXPECT_LT(sent, held);
}

// A ghost that the holder's pass pushed although its owner's did not (a force seen on one rank
// only) would part from its owner's state: an error on the holder.
TEST(Domain, AGhostPushedOnlyOnItsHolderIsAnError) {
  const RankTeam world = RankTeam::world();
  Row row(world);
  const auto update = [&] {
    row.domain.update_ghosts(
        1, [&](std::uint32_t i) { return !row.owned[i]; }, [](std::uint32_t, double*) {},
        [](std::uint32_t, const double*) {});
  };
  if (row.ghosts() > 0)
    EXPECT_THROW(update(), std::logic_error);
  else
    update();
}

}  // namespace
}  // namespace granjet::dem
