// Neighbour lists with shells (event_driven/neighbour_shells.hpp), the event-driven backend's
// search in dense 3D periodic gases: the lists are those of a search over all pairs, after a
// build and after renewals; the renewal time is when the grain reaches its shell; and a
// simulator on lists finds the collisions a simulator on cells does from the same state, conserves
// momentum and energy, runs deterministically and resumes from a checkpoint bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "core/initial_state.hpp"
#include "core/random.hpp"
#include "core/state_archive.hpp"
#include "event_driven/ed_simulator.hpp"
#include "event_driven/neighbour_shells.hpp"
#include "event_driven/scene_support.hpp"
#include "run/scene_file.hpp"

namespace granjet::ed {
namespace {

using Shells = NeighbourShells<3>;

// Every pair (i < k) whose nearest images lie within kShell (r_i + r_k).
std::set<std::pair<std::uint32_t, std::uint32_t>> all_pairs_within(const std::vector<Vec<3>>& x,
                                                                   const std::vector<double>& r,
                                                                   const PeriodicBox<3>& box) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < x.size(); ++i)
    for (std::uint32_t k = i + 1; k < x.size(); ++k)
      if (box.separation(x[k], x[i]).norm() < Shells::kShell * (r[i] + r[k])) pairs.insert({i, k});
  return pairs;
}

// The pairs the lists hold, each found from both sides.
std::set<std::pair<std::uint32_t, std::uint32_t>> listed_pairs(const Shells& shells,
                                                               std::size_t n) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t k : shells.of(i)) {
      const auto back = shells.of(k);
      EXPECT_EQ(std::count(back.begin(), back.end(), i), 1) << i << " listed by " << k;
      pairs.insert({std::min(i, k), std::max(i, k)});
    }
  return pairs;
}

TEST(NeighbourShells, ListsAreThePairsWithinTheShellAfterBuildAndRenewals) {
  const Vec<3> box(9.0, 10.0, 11.0);
  const std::size_t n = 2500;  // overlapping, so dense that some lists outgrow their first room
  Random rng(3);
  std::vector<Vec<3>> x(n);
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) x[i][a] = box[a] * rng.uniform();
    r[i] = 0.35 + 0.15 * rng.uniform();  // polydisperse, largest diameter 1
  }
  ASSERT_TRUE(Shells::fits(box, 1.0));
  Shells shells(r, box);
  const std::vector<std::uint8_t> live(n, 1);
  shells.build(x, live);
  const PeriodicBox<3> space(box);
  EXPECT_EQ(listed_pairs(shells, n), all_pairs_within(x, r, space));
  std::size_t longest = 0;
  for (std::uint32_t i = 0; i < n; ++i) longest = std::max(longest, shells.of(i).size());
  EXPECT_GT(longest, 32u);
  // Grains move anywhere, across the box's faces too, and renew one at a time.
  for (int round = 0; round < 300; ++round) {
    const auto i = static_cast<std::uint32_t>(rng.below(n));
    for (int a = 0; a < 3; ++a) x[i][a] = box[a] * rng.uniform();
    shells.renew(i, x[i]);
  }
  EXPECT_EQ(listed_pairs(shells, n), all_pairs_within(x, r, space));
}

TEST(NeighbourShells, RenewalComesWhenTheGrainReachesItsShell) {
  const Vec<3> box = Vec<3>::Constant(10.0);
  Shells shells({0.5}, box);
  const Vec<3> centre(5.0, 5.0, 5.0);
  shells.build(std::vector<Vec<3>>{centre}, std::vector<std::uint8_t>{1});
  const double reach = (Shells::kShell - 1.0) * 0.5;
  const Vec<3> v(0.3, -0.4, 1.2);  // |v| = 1.3
  // From the centre, from halfway out moving out, and from halfway out moving back in.
  EXPECT_NEAR(shells.exit_delay(0, centre, v), reach / 1.3, 1e-14);
  EXPECT_NEAR(shells.exit_delay(0, centre + 0.5 * reach * v / 1.3, v), 0.5 * reach / 1.3, 1e-14);
  EXPECT_NEAR(shells.exit_delay(0, centre - 0.5 * reach * v / 1.3, v), 1.5 * reach / 1.3, 1e-14);
  EXPECT_EQ(shells.exit_delay(0, centre, Vec<3>::Zero()), kNever);
}

// The shipped elastic gas at phi = 0.45, as the event-driven backend takes it.
Scene dense_gas(std::int64_t grains) {
  return hard_scene(load_scene(std::string(GRANJET_SCENES_DIR) + "/gas3d.ini",
                               {"gas.phi=0.45", "gas.grains=" + std::to_string(grains)}));
}

// Each pair's collisions in order, as the impulses on the pair's first grain.
std::map<std::pair<GrainId, GrainId>, std::vector<Vec<3>>> by_pair(
    const std::vector<PairImpulse<3>>& transfers) {
  std::map<std::pair<GrainId, GrainId>, std::vector<Vec<3>>> pairs;
  for (const PairImpulse<3>& t : transfers)
    pairs[{std::min(t.i, t.j), std::max(t.i, t.j)}].push_back(t.i < t.j ? t.impulse
                                                                        : Vec<3>(-t.impulse));
  return pairs;
}

// The lists and the cells find the same collisions: over the first ~3 collisions per grain
// (before round-off, which the two take differently in the nearest image, has grown) every
// pair collides as often, with the same impulses to 1e-9. (Collisions of different pairs at
// times equal to rounding may pop in either order.)
TEST(NeighbourLists, SameCollisionsAsTheCells) {
  const Scene scene = dense_gas(2048);
  EdSimulator<3> lists(scene, build_initial_state<3>(scene), Verification::kOn);
  EdSimulator<3> cells(scene, build_initial_state<3>(scene), Verification::kOn,
                       NeighbourSearch::kCells);
  lists.record_transfers(true);
  cells.record_transfers(true);
  lists.advance_to(0.3);
  cells.advance_to(0.3);
  EXPECT_GT(lists.stats().neighbour_rebuilds, 0);  // the lists are in use, and renew
  EXPECT_EQ(cells.stats().neighbour_rebuilds, 0);
  std::vector<PairImpulse<3>> a, b;
  lists.collect_transfers(a);
  cells.collect_transfers(b);
  ASSERT_GT(a.size(), 5000u);
  ASSERT_EQ(a.size(), b.size());
  const auto pa = by_pair(a), pb = by_pair(b);
  ASSERT_EQ(pa.size(), pb.size());
  for (const auto& [pair, impulses] : pa) {
    const auto other = pb.find(pair);
    ASSERT_NE(other, pb.end()) << pair.first << "-" << pair.second;
    ASSERT_EQ(impulses.size(), other->second.size()) << pair.first << "-" << pair.second;
    for (std::size_t m = 0; m < impulses.size(); ++m)
      EXPECT_LT((impulses[m] - other->second[m]).norm(), 1e-9) << pair.first << "-" << pair.second;
  }
}

// Asking for the state more or less often leaves the listed run bit for bit the same, and a run
// resumed from a checkpoint (which renews every list) is the straight run, every digit.
TEST(NeighbourLists, DeterministicAndResumedBitIdentically) {
  const Scene scene = dense_gas(500);
  EdSimulator<3> once(scene, build_initial_state<3>(scene));
  EdSimulator<3> often(scene, build_initial_state<3>(scene));
  once.advance_to(1.0);
  for (int k = 1; k <= 100; ++k) often.advance_to(0.01 * k);
  StateArchive archive, also;  // a checkpoint is part of the run: both take one
  once.checkpoint(archive);
  often.checkpoint(also);
  once.advance_to(2.0);
  EdSimulator<3> resumed(scene, build_initial_state<3>(scene));
  resumed.restore(archive);
  resumed.advance_to(2.0);
  often.advance_to(2.0);
  ASSERT_GT(once.stats().neighbour_rebuilds, 100);
  // Elastic: momentum (zero at the start) and energy stay.
  Vec<3> momentum = Vec<3>::Zero();
  for (const Vec<3>& v : once.particles().velocity()) momentum += v;
  EXPECT_LT(momentum.norm(), 1e-10);
  EXPECT_LT(std::abs(once.energy().dissipated), 1e-9 * once.energy().kinetic);
  for (const EdSimulator<3>* other : {&often, &resumed}) {
    EXPECT_EQ(once.stats().collisions, other->stats().collisions);
    EXPECT_TRUE(std::equal(once.particles().position().begin(), once.particles().position().end(),
                           other->particles().position().begin()));
    EXPECT_TRUE(std::equal(once.particles().velocity().begin(), once.particles().velocity().end(),
                           other->particles().velocity().begin()));
  }
}

}  // namespace
}  // namespace granjet::ed
