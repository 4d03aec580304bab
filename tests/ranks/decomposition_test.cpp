// One soft-DEM run spread over the MPI ranks this test was started on (mpirun -n K, K = 2..4)
// gives the one-rank run's grains bit for bit, in the same order, with the same energies and
// counts: both integrators, friction on and off, the tethered and fixed targets, the plate
// and the removal of escaped grains. Every rank runs the one-rank simulation alongside and
// compares: the energies and counts on every rank, the grains and samples on rank 0, the
// only one that holds them whole (the others hold none). Also the parts' bisection over ranks
// and the work balance that decides when to cut them anew.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "../common/raw_state.hpp"
#include "analysis/checkpoint_file.hpp"
#include "analysis/field_accumulator.hpp"
#include "core/archive_shares.hpp"
#include "core/jet_geometry.hpp"
#include "core/rank_team.hpp"
#include "core/recursive_bisection.hpp"
#include "core/sample_region.hpp"
#include "core/state_archive.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "soft_dem/work_balance.hpp"

namespace granjet {
namespace {

template <int D>
std::vector<double> raw_state(const Particles<D>& p) {
  std::vector<double> out;
  for (std::size_t i = 0; i < p.size(); ++i) testing::append_raw_state(out, p, i);
  return out;
}

bool on_rank0() { return RankTeam::world().rank() == 0; }

// What only rank 0 holds whole: the one-rank run's on rank 0, nothing elsewhere.
template <class T>
void expect_whole_on_rank0(const std::vector<T>& one, const std::vector<T>& spread,
                           const std::string& what) {
  if (!on_rank0()) {
    EXPECT_TRUE(spread.empty()) << what << ": rank " << RankTeam::world().rank() << " holds some";
    return;
  }
  ASSERT_EQ(one.size(), spread.size()) << what;
  EXPECT_EQ(0, std::memcmp(one.data(), spread.data(), one.size() * sizeof(T)))
      << what << ": differs from the one-rank run's";
}

std::vector<double> energies(const EnergyBalance& e) {
  return {e.kinetic, e.rotational, e.elastic, e.removed, e.dissipated};
}

// Both runs to t: the same grains (whole on rank 0) and energies.
template <int D>
void advance_both_and_compare(Simulator<D>& one, Simulator<D>& spread, double t) {
  one.advance_to(t);
  spread.advance_to(t);
  expect_whole_on_rank0(raw_state(one.particles()), raw_state(spread.particles()),
                        "the grains at t = " + std::to_string(t));
  EXPECT_EQ(energies(one.energy()), energies(spread.energy())) << "t = " << t;
}

// The same transfers in the same order, bit for bit.
template <int D>
void expect_same_transfers(const std::vector<PairImpulse<D>>& a,
                           const std::vector<PairImpulse<D>>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t c = 0; c < a.size(); ++c) {
    EXPECT_EQ(a[c].i, b[c].i);
    EXPECT_EQ(a[c].j, b[c].j);
    EXPECT_EQ(a[c].position_i, b[c].position_i);
    EXPECT_EQ(a[c].position_j, b[c].position_j);
    EXPECT_EQ(a[c].impulse, b[c].impulse);
  }
}

// The sampled forces and transfers, in the order and with the bits of one rank.
template <int D>
void expect_samples_of_one_rank(Simulator<D>& one, Simulator<D>& spread) {
  ForceSample<D> a, b;
  one.sample_forces(a);
  spread.sample_forces(b);
  std::vector<PairImpulse<D>> ta, tb;
  one.collect_transfers(ta);
  spread.collect_transfers(tb);
  if (!on_rank0()) {
    EXPECT_TRUE(b.contacts.empty() && b.total.empty() && tb.empty());
    return;
  }
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t c = 0; c < a.contacts.size(); ++c) {
    EXPECT_EQ(a.contacts[c].i, b.contacts[c].i);
    EXPECT_EQ(a.contacts[c].j, b.contacts[c].j);
    EXPECT_EQ(a.contacts[c].normal_force, b.contacts[c].normal_force);
    EXPECT_EQ(a.contacts[c].tangential_force, b.contacts[c].tangential_force);
    EXPECT_EQ(a.contacts[c].overlap, b.contacts[c].overlap);
  }
  EXPECT_EQ(a.total, b.total);
  expect_same_transfers(ta, tb);
}

// A frame as it comes to a sink: its grains' state, forces and contacts by id, that its
// stretches of ids came in order, each with its own grains only, and in how many pieces its
// contacts came.
template <int D>
struct RecordedFrame final : FrameSink<D> {
  std::vector<std::vector<double>> rows;  // by id: raw_state, then the force
  std::vector<std::uint8_t> held;
  std::vector<double> touching;  // the contacts as raw numbers
  std::size_t stretches = 0, contact_pieces = 0, largest_piece = 0;
  GrainId done = 0;
  bool in_order = true;

  explicit RecordedFrame(std::size_t ids) : rows(ids), held(ids, 0) {}
  void grains(GrainId first, GrainId end, const Particles<D>& grains,
              std::span<const Vec<D>> force) override {
    ++stretches;
    in_order = in_order && first == done && end >= first;
    done = end;
    for (std::size_t k = 0; k < grains.size(); ++k) {
      const GrainId id = grains.id()[k];
      in_order = in_order && id >= first && id < end;
      Particles<D> one;
      one.add(id, grains.kind()[k], grains.position()[k], grains.velocity()[k], grains.radius()[k],
              grains.mass()[k]);
      one.spin()[0] = grains.spin()[k];
      rows.at(id) = raw_state(one);
      rows[id].push_back(grains.radius()[k]);
      if (!force.empty()) rows[id].insert(rows[id].end(), force[k].data(), force[k].data() + D);
      held[id] = 1;
    }
  }
  void contacts(std::span<const typename ForceSample<D>::Contact> list) override {
    ++contact_pieces;
    largest_piece = std::max(largest_piece, list.size());
    for (const auto& c : list) {
      touching.insert(touching.end(),
                      {static_cast<double>(c.i), static_cast<double>(c.j), c.overlap});
      touching.insert(touching.end(), c.normal_force.data(), c.normal_force.data() + D);
      touching.insert(touching.end(), c.tangential_force.data(), c.tangential_force.data() + D);
    }
  }
};

// The frame over ranks, in stretches of `block` ids and its contacts in pieces of about as
// many, is the one-rank frame, and only rank 0 hears of it. A piece holds more only where one
// cell does: never with 97, often with 5 (where sticky grains crowd a cell with contacts).
// On rank 0, `pieces` says how many contacts came in how many pieces.
struct ContactPieces {
  std::size_t contacts = 0, pieces = 0;
};
template <int D>
void expect_frame_of_one_rank(const Simulator<D>& one, const Simulator<D>& spread,
                              std::size_t block, ContactPieces& pieces) {
  const std::size_t ids = one.grain_count() + one.stats().removed;
  EXPECT_EQ(one.grain_count(), spread.grain_count());
  const FrameAsk ask{ids, block, true, true};
  RecordedFrame<D> a(ids), b(ids);
  one.frame(ask, a);
  spread.frame(ask, b);
  if (!on_rank0()) {
    EXPECT_EQ(b.stretches, 0u);
    EXPECT_EQ(b.contact_pieces, 0u);
    return;
  }
  pieces = {a.touching.size() / (3 + 2 * D), b.contact_pieces};
  EXPECT_EQ(b.stretches, (ids + block - 1) / block);
  EXPECT_TRUE(b.in_order);
  EXPECT_EQ(static_cast<std::size_t>(b.done), ids);
  EXPECT_EQ(a.held, b.held);
  EXPECT_GT(std::count(b.held.begin(), b.held.end(), 1), 0);
  for (std::size_t id = 0; id < ids; ++id) {
    ASSERT_EQ(a.rows[id].size(), b.rows[id].size()) << "grain " << id;
    ASSERT_EQ(0,
              std::memcmp(a.rows[id].data(), b.rows[id].data(), a.rows[id].size() * sizeof(double)))
        << "grain " << id;
  }
  if (block >= 97) {
    EXPECT_LE(b.largest_piece, block);
  }
  ASSERT_EQ(a.touching.size(), b.touching.size());  // none in flight; some at the end
  EXPECT_EQ(0,
            std::memcmp(a.touching.data(), b.touching.data(), a.touching.size() * sizeof(double)));
}

template <int D>
void expect_ranks_give_one_rank_bits(const std::string& scene_file,
                                     std::vector<std::string> overrides, double t_end,
                                     bool expect_removal = false) {
  const RankTeam world = RankTeam::world();
  ASSERT_GT(world.size(), 1) << "start this test with mpirun -n K, K > 1";
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/" + scene_file, overrides);
  auto one = dem::make_dem_simulator<D>(scene);
  auto spread = dem::make_dem_simulator<D>(scene, world);
  // Compared at several times, so that rebuilds, moves and re-cuts come between.
  for (double t : {0.25 * t_end, t_end}) {
    advance_both_and_compare(*one, *spread, t);
    const SimStats a = one->stats(), b = spread->stats();
    EXPECT_EQ(a.steps, b.steps);
    EXPECT_EQ(a.particle_steps, b.particle_steps);
    EXPECT_EQ(a.contacts, b.contacts);
    EXPECT_EQ(a.neighbour_rebuilds, b.neighbour_rebuilds);
    EXPECT_EQ(a.removed, b.removed);
    // The ghosts that no force pushed coasted on their holders: their owners sent no state.
    EXPECT_GT(b.ghost_states_per_step, 0.0);
    EXPECT_GT(b.ghost_states_share, 0.0);
    EXPECT_LT(b.ghost_states_share, 1.0);
    expect_samples_of_one_rank<D>(*one, *spread);
    ContactPieces coarse, fine;
    expect_frame_of_one_rank<D>(*one, *spread, 97, coarse);
    expect_frame_of_one_rank<D>(*one, *spread, 5, fine);
    if (coarse.contacts > 2 * 97) {  // more than a stretch's worth: in pieces, finer for 5
      EXPECT_GT(coarse.pieces, 1u);
      EXPECT_GT(fine.pieces, coarse.pieces);
    }
  }
  EXPECT_GT(one->stats().contacts, 10);
  if (expect_removal) {
    EXPECT_GT(one->stats().removed, 0);
  }
}

// Cut lengthwise: jet2d's strip is 30 d wide, its reach 1.3 d (soft_dem/jet_cuts.hpp).
TEST(Ranks, Jet2dFrictionalBidisperseAb2CutLengthwise) {
  expect_ranks_give_one_rank_bits<2>(
      "jet2d.ini", {"jet.grains=1500", "contact.friction=0.5", "run.lengthwise_cuts=auto"}, 4.0);
}

TEST(Ranks, Jet2dFrictionlessTetheredTargetWithRemoval) {
  expect_ranks_give_one_rank_bits<2>(
      "jet2d.ini", {"jet.grains=1500", "contact.friction=0", "jet.diameter=10", "region.radius=6"},
      12.0, true);
}

TEST(Ranks, Jet3dFrictionalVerlet) {
  expect_ranks_give_one_rank_bits<3>(
      "jet3d.ini", {"jet.grains=2000", "run.integrator=verlet", "wall.diameter=14"}, 3.0);
}

TEST(Ranks, Jet3dOnTheFrictionalPlateWithRollingResistance) {
  expect_ranks_give_one_rank_bits<3>(
      "jet3d.ini",
      {"jet.grains=2000", "contact.rolling_friction=0.1", "wall.kind=plate", "wall.diameter=14"},
      3.0);
}

// The other contact law and the cohesive pull: each ghost pair's force as on one rank.
TEST(Ranks, Jet3dHertzMindlinWithAdhesion) {
  expect_ranks_give_one_rank_bits<3>(
      "jet3d.ini",
      {"jet.grains=2000", "contact.model=hertz", "contact.adhesion=0.05", "wall.diameter=14"}, 3.0);
}

TEST(Ranks, Jet3dFixedTargetWithThreads) {
  // Ranks times threads beyond a small machine's cores only wait on each other.
  if (RankTeam::world().size() > 2) GTEST_SKIP() << "two threads on each of two ranks only";
  expect_ranks_give_one_rank_bits<3>(
      "jet3d.ini", {"jet.grains=2000", "wall.kind=fixed", "wall.diameter=14", "run.threads=2"},
      3.0);
}

TEST(Ranks, Jet3dFrictionlessBidisperseAb2) {
  expect_ranks_give_one_rank_bits<3>("jet3d.ini",
                                     {"jet.grains=2000", "wall.diameter=14", "contact.friction=0",
                                      "jet.dispersity=bi", "jet.small_diameter=0.8"},
                                     3.0);
}

// Fewer grains than ranks on a frictional plate: some rank holds no grain at every rebuild,
// while the plate keeps a tangential-history slot for each grain (the law is frictional) that
// moves with its grain between ranks. The grains fall onto the plate and bounce.
TEST(Ranks, RanksWithoutGrainsOnTheFrictionalPlate) {
  const RankTeam world = RankTeam::world();
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                                 {"jet.grains=" + std::to_string(world.size() - 1),
                                  "wall.kind=plate", "wall.diameter=14", "contact.friction=0.5"});
  auto one = dem::make_dem_simulator<3>(scene);
  auto spread = dem::make_dem_simulator<3>(scene, world);
  for (double t : {2.0, 4.0, 8.0}) {
    advance_both_and_compare(*one, *spread, t);
    EXPECT_EQ(one->stats().neighbour_rebuilds, spread->stats().neighbour_rebuilds);
  }
  EXPECT_GT(one->stats().neighbour_rebuilds, 10);
  EXPECT_GT(one->energy().dissipated, 0.0) << "the grains never reached the plate";
}

// Two grains, one per part: their contact crosses ranks for its whole duration, and its
// tangential history (an oblique, frictional impact) lives on both owners. Compared during the
// contact and after it; with more ranks than grains some ranks own none.
TEST(Ranks, AContactAcrossRanksKeepsItsHistory) {
  const RankTeam world = RankTeam::world();
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/binary.ini",
                                 {"binary.impact_parameter=0.5", "contact.friction=0.5"});
  auto one = dem::make_dem_simulator<3>(scene);
  auto spread = dem::make_dem_simulator<3>(scene, world);
  const auto x = one->particles().position();
  const std::vector<double> weight(x.size(), 1.0);
  const RecursiveBisection<3> parts(x, weight, world.size());
  ASSERT_EQ(parts.part().size(), 2u);
  ASSERT_NE(parts.part()[0], parts.part()[1]) << "the two grains start on one rank";
  for (double t : {0.09, 0.12, 0.5}) {
    advance_both_and_compare(*one, *spread, t);
    EXPECT_EQ(one->stats().contacts, spread->stats().contacts) << "t = " << t;
    EXPECT_EQ(one->stats().contacts, t < 0.2 ? 1 : 0) << "t = " << t;
    expect_samples_of_one_rank<3>(*one, *spread);
  }
}

// jet3d of 2,000 grains on a 14-d target at t = 3, on one rank and over the ranks, and its
// front: the lowest jet grain's height, with the impact's contacts just above it.
struct JetAtItsFront {
  std::unique_ptr<Simulator<3>> one, spread;
  double front = INFINITY;
};
JetAtItsFront jet_at_its_front() {
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                                 {"jet.grains=2000", "wall.diameter=14"});
  JetAtItsFront jet{dem::make_dem_simulator<3>(scene),
                    dem::make_dem_simulator<3>(scene, RankTeam::world())};
  jet.one->advance_to(3.0);
  jet.spread->advance_to(3.0);
  const Particles<3>& p = jet.one->particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.kind()[i] == GrainKind::kFree)
      jet.front = std::min(jet.front, p.position()[i][kJetAxis<3>]);
  return jet;
}

// A look at part of the run (an analysis sample, core/sample_region.hpp) gets on rank 0 exactly
// the one-rank run's grains and transfers that the region holds, in its order, and nothing
// elsewhere; particles() afterwards is the whole again. First the grains beyond a distance from
// the jet axis (outside the analysis window), then those and the contacts in a cylinder about
// it, cut across the jet's front (the window's bins).
TEST(Ranks, ASampleRegionGetsTheOneRankRunsGrainsAndTransfersInIt) {
  const auto [one, spread, front] = jet_at_its_front();
  const Particles<3>& whole = one->particles();
  const auto across = [](Vec<3> x) {
    x[kJetAxis<3>] = 0.0;
    return x.norm();
  };
  const auto expect_held = [&](const SampleRegion& region, const std::string& what) {
    std::vector<std::uint32_t> held;
    for (std::uint32_t i = 0; i < whole.size(); ++i)
      if (region.holds_grain<3>(whole.position()[i], whole.radius()[i], whole.kind()[i]))
        held.push_back(i);
    ASSERT_GT(held.size(), 10u) << what;
    ASSERT_LT(held.size(), whole.size() * 3 / 4) << what;
    Particles<3> expected = whole;
    expected.gather(held, 1);
    expect_whole_on_rank0(raw_state(expected), raw_state(spread->particles_in(region)), what);
  };
  const double radius = 4.0;
  for (std::uint32_t i = 0; i < whole.size(); ++i) {
    const double r = across(whole.position()[i]);
    ASSERT_FALSE(r > radius * (1.0 - 1e-6) && r <= radius) << "a grain on the edge: move it";
  }
  expect_held({.beyond = radius}, "the grains beyond r = 4");

  const SampleRegion cylinder{.within = 2.5, .low = front - 1.0, .high = front + 1.5};
  expect_held(cylinder, "the grains at the front");
  std::vector<PairImpulse<3>> all, expected, got;
  one->collect_transfers_in(all, cylinder);
  spread->collect_transfers_in(got, cylinder);
  for (const PairImpulse<3>& t : all)
    if (cylinder.holds_transfer<3>(t.position_i, t.position_j)) expected.push_back(t);
  ASSERT_GT(expected.size(), 10u);
  ASSERT_LT(expected.size(), all.size());
  if (on_rank0())
    expect_same_transfers(expected, got);
  else
    EXPECT_TRUE(got.empty());
  expect_whole_on_rank0(raw_state(whole), raw_state(spread->particles()), "then all grains");
}

// Each rank's archive through a checkpoint file, written by rank 0 as a run's is (rank r's
// share comes when asked for); each rank reads back its own shares. Collective.
StateArchive through_checkpoint_file(const RankTeam& world, const StateArchive& mine,
                                     const std::string& name) {
  const std::vector<std::byte> share = share_bytes(mine);
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("granjet_ranks_" + name + "_" + std::to_string(world.size()) + ".h5.checkpoint");
  if (on_rank0())
    analysis::write_checkpoint_file(file, mine,
                                    [&](int r) { return share_on_rank0(world, r, share); });
  else
    for (int r = 1; r < world.size(); ++r) share_on_rank0(world, r, share);
  world.any(false);  // the file is whole before any rank reads it
  StateArchive read = analysis::read_checkpoint_file(file, {world.rank(), world.size()});
  world.any(false);
  if (on_rank0()) std::filesystem::remove(file);
  return read;
}

// Rank 0's velocity statistics after a join, against one process's, bit for bit: the flatness
// of each of `bins` bins and of all pooled, the region's, the density.
void expect_same_velocity_statistics(const analysis::VelocityDistribution<3>& alone,
                                     const analysis::VelocityDistribution<3>& joined, int bins,
                                     const std::string& what) {
  if (!on_rank0()) return;
  const auto same = [](double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
  };
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(std::isfinite(alone.flatness(c))) << what;
    for (int bin = -1; bin < bins; ++bin)
      EXPECT_TRUE(same(alone.flatness(c, bin), joined.flatness(c, bin)))
          << what << ", component " << c << ", bin " << bin;
    EXPECT_TRUE(same(alone.flatness_region(c), joined.flatness_region(c)))
        << what << ", component " << c;
    const std::vector<double> a = alone.density(c), b = joined.density(c);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_TRUE(same(a[k], b[k])) << what << ", component " << c << ", interval " << k;
  }
}

// Velocities dealt out to the ranks: each keeps its own, and the join gives rank 0 the
// statistics of all of them, bit for bit (a bin with no spread in z included).
TEST(Ranks, VelocityDistributionsJoinTheStatisticsOfEveryRanksValues) {
  const RankTeam world = RankTeam::world();
  analysis::VelocityDistribution<3> all(3), mine(3);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < 3000; ++k) {
    const int bin = k % 3;
    const Vec<3> v(1.0 + (bin + 1) * g(rng), 0.5 * g(rng) * g(rng), bin == 2 ? 0.25 : g(rng));
    all.add(bin, v);
    if (k % world.size() == world.rank()) mine.add(bin, v);
  }
  mine.join(world);
  EXPECT_EQ(mine.size(), (3000 - world.rank() + world.size() - 1) / world.size());
  EXPECT_TRUE(std::isnan(all.flatness(2, 2)));
  EXPECT_GT(all.flatness(1), 4.0);  // a product of two Gaussians: flatness 9
  expect_same_velocity_statistics(all, mine, 3, "dealt out");
}

// The inline analysis' bins over ranks (Simulator::sample_own, join_samples): each rank sums the
// grains it owns and the contacts it lists, the join brings every rank's sums to rank 0, and
// rank 0's fields are the one-rank run's, bit for bit; the other ranks are left with none.
// The velocity distributions' values stay with their ranks, in a checkpoint too.
TEST(Ranks, EachRankSumsItsOwnBinsAndTheJoinIsTheOneRankRuns) {
  const auto [one, spread, front] = jet_at_its_front();
  const analysis::BinSpec spec{4.0, front - 0.5, 4, 2, 1.5};  // straddling the contacts
  const int spec_bins = 4 * 2;
  analysis::FieldAccumulator<3> alone(spec), mine(spec);
  for (double t : {3.0, 3.5, 4.0}) {
    one->advance_to(t);
    spread->advance_to(t);
    const double elapsed = t == 3.0 ? 0.0 : 0.5;
    one->sample_own(alone.reach(), elapsed, alone);
    spread->sample_own(alone.reach(), elapsed, mine);
  }
  spread->join_samples(mine);
  const analysis::Table expected = alone.fields({}), got = mine.fields({});
  ASSERT_EQ(expected.names(), got.names());
  int finite = 0;
  for (const std::string& name : expected.names())
    for (std::size_t bin = 0; bin < expected.rows(); ++bin) {
      const double a = expected.at(bin, name), b = got.at(bin, name);
      if (name == "n") {
        EXPECT_GT(a, 0.0) << "bin " << bin << " holds no grain";
      }
      finite += std::isfinite(a);
      if (on_rank0()) {
        EXPECT_TRUE(std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)))
            << name << " in bin " << bin << ": " << a << " against " << b;
      } else if (name == "n") {
        EXPECT_EQ(b, 0.0) << "bin " << bin << " after the join";
      }
    }
  EXPECT_GT(finite, static_cast<int>(expected.rows() * expected.names().size() / 2));
  EXPECT_GT(alone.fields({}).at(0, "contact_density"), 0.0);
  expect_same_velocity_statistics(alone.velocity_distribution(), mine.velocity_distribution(),
                                  spec_bins, "joined");

  // Each rank keeps its grains' velocities: a checkpoint holds them in the rank's share, and
  // the ranks that resume from it read them back and join the same statistics.
  const RankTeam world = RankTeam::world();
  StateArchive own;
  own.split_over(world.size(), {});
  StateWriter own_writer(own, "fields");
  mine.save_own(own_writer);
  const StateArchive read = through_checkpoint_file(world, own, "bins");
  analysis::FieldAccumulator<3> resumed(spec);
  StateReader own_reader(read, "fields");
  resumed.restore_own(own_reader);
  EXPECT_EQ(resumed.velocity_distribution().size(), mine.velocity_distribution().size());
  resumed.join(world);
  expect_same_velocity_statistics(alone.velocity_distribution(), resumed.velocity_distribution(),
                                  spec_bins, "read back from the ranks' shares");

  // A checkpoint of one process holds all of them for rank 0: the other ranks take none.
  StateArchive whole;
  StateWriter whole_writer(whole, "fields");
  alone.save_own(whole_writer);
  StateArchive as_read;  // the entries as a reader finds them: none from a share
  for (const auto& [name, values] : whole.all_integers()) as_read.put_integers(name, values);
  for (const auto& [name, values] : whole.all_reals()) as_read.put_reals(name, values);
  analysis::FieldAccumulator<3> from_one(spec);
  StateReader whole_reader(as_read, "fields");
  from_one.restore_own(whole_reader);
  EXPECT_EQ(from_one.velocity_distribution().size(), 0u);
}

// The bisection over ranks, of points dealt out to the ranks in turn, gives the regions that
// one process cuts from all the points: its sums are exact integers, whatever the split.
TEST(Ranks, BisectionOverRanksIsTheSameForAnySplitOfThePoints) {
  const RankTeam world = RankTeam::world();
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-5.0, 5.0), heavy(0.1, 9.0);
  std::vector<Vec<3>> x(3000);
  std::vector<double> w(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = Vec<3>(u(rng), 0.3 * u(rng), std::floor(u(rng)));  // z: layers
    w[i] = heavy(rng);
  }
  std::vector<Vec<3>> mine_x;
  std::vector<double> mine_w;
  for (std::size_t i = world.rank(); i < x.size(); i += world.size()) {
    mine_x.push_back(x[i]);
    mine_w.push_back(w[i]);
  }
  for (int parts : {world.size(), 5, 16}) {
    const auto spread = RecursiveBisection<3>::over_ranks(world, mine_x, mine_w, parts);
    const auto alone = RecursiveBisection<3>::over_ranks(RankTeam(), x, w, parts);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) differ += spread.part_of(x[i]) != alone.part()[i];
    EXPECT_EQ(differ, 0u) << parts << " parts";
    for (std::size_t k = 0; k < mine_x.size(); ++k)
      ASSERT_EQ(spread.part()[k], spread.part_of(mine_x[k]));
  }
}

// The balance compares the ranks' pass time every kRebuildsPerLook rebuilds (the first look,
// at the run's first rebuild, has nothing to compare) and, the busiest rank over the mean by
// more than kRecutImbalance, has every rank cut anew with its own work. Rank 0 passes 40 ms,
// the others 10 ms.
TEST(Ranks, WorkBalanceCutsAnewWhenTheBusiestRankPassesTheMean) {
  using dem::WorkBalance;
  const RankTeam world = RankTeam::world();
  WorkBalance balance;
  EXPECT_TRUE(balance.looks_at_next_rebuild());
  EXPECT_FALSE(balance.at_rebuild(world));
  const double mine = world.rank() == 0 ? 0.040 : 0.010;
  {
    const WorkBalance::Pass pass(balance);
    std::this_thread::sleep_for(std::chrono::duration<double>(mine));
  }
  for (int k = 1; k < WorkBalance::kRebuildsPerLook; ++k) {
    EXPECT_FALSE(balance.looks_at_next_rebuild());
    EXPECT_FALSE(balance.at_rebuild(world));
  }
  ASSERT_TRUE(balance.looks_at_next_rebuild());
  const std::optional<double> work = balance.at_rebuild(world);
  ASSERT_TRUE(work.has_value()) << "no re-cut";
  EXPECT_GE(*work, mine);
  EXPECT_LT(*work, mine + 0.030);
  const double mean = (0.040 + 0.010 * (world.size() - 1)) / world.size();
  EXPECT_GT(balance.imbalance(), 0.5 * (1.0 + 0.040 / mean));
  EXPECT_EQ(balance.recuts(), 1);
}

// A re-cut whose moves cost more than the imbalance wasted waits until the waste since the
// last re-cut has grown past that cost (the slowest rank's), then cuts and starts counting anew.
TEST(Ranks, WorkBalanceWaitsUntilARecutWouldPayForItsMoves) {
  using dem::WorkBalance;
  const RankTeam world = RankTeam::world();
  WorkBalance balance;
  ASSERT_FALSE(balance.at_rebuild(world));  // the start
  balance.recut_took(world.rank() == 1 ? 0.050 : 0.0);
  // Rank 0 works 30 ms a look more than each other rank: 15-22.5 ms beyond the mean.
  const auto look = [&] {
    {
      const WorkBalance::Pass pass(balance);
      std::this_thread::sleep_for(std::chrono::milliseconds(world.rank() == 0 ? 40 : 10));
    }
    return balance.at_rebuild(world).has_value();
  };
  EXPECT_FALSE(look()) << "a re-cut at 15-22.5 ms of waste, against 50 ms of moves";
  int looks = 1;
  while (!look()) ASSERT_LE(++looks, 6) << "no re-cut after 6 looks of 15 ms or more of waste";
  EXPECT_GE(looks, 2);
  EXPECT_EQ(balance.recuts(), 1);
  EXPECT_FALSE(look()) << "the waste counts anew after a re-cut";
}

// A checkpoint written over K ranks resumes on one rank, and one written on one rank resumes
// over K, each going on as the run that wrote it. Over K ranks each rank's archive holds its own
// share of the grains and contacts: rank 0 joins the others' to its own for one rank, and the
// checkpoint file stores them apart, each rank reading back its own (its contacts' partners
// may be another's).
TEST(Ranks, CheckpointResumesOnAnotherRankCount) {
  const RankTeam world = RankTeam::world();
  const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                                 {"jet.grains=2000", "wall.diameter=14", "contact.friction=0.5"});
  auto one = dem::make_dem_simulator<3>(scene);
  auto spread = dem::make_dem_simulator<3>(scene, world);
  one->advance_to(2.0);
  spread->advance_to(2.0);
  StateArchive from_one, from_spread;
  one->checkpoint(from_one);
  spread->checkpoint(from_spread);
  EXPECT_EQ(from_spread.ranks(), world.size());
  StateArchive joined = from_spread;  // rank 0's and, in rank order, the others' shares
  const std::vector<std::byte> share = share_bytes(from_spread);
  for (int r = 1; r < world.size(); ++r) joined.append_share(share_on_rank0(world, r, share));

  const StateArchive mine = through_checkpoint_file(world, from_spread, "checkpoint");
  EXPECT_LT(mine.integers("dem/grains/id").size(), from_one.integers("dem/grains/id").size());
  // Some contact's partner is another rank's to read: the resume hands its history on.
  const std::vector<std::int64_t>& ids = mine.integers("dem/grains/id");
  const std::vector<std::int64_t>& pairs = mine.integers("dem/history/pair");
  bool partner_elsewhere = false;
  for (std::size_t k = 1; k < pairs.size(); k += 2)
    partner_elsewhere |= std::find(ids.begin(), ids.end(), pairs[k]) == ids.end();
  EXPECT_TRUE(world.any(partner_elsewhere));

  auto spread_resumed = dem::make_dem_simulator<3>(scene, world);
  spread_resumed->restore(from_one);
  auto spread_from_file = dem::make_dem_simulator<3>(scene, world);
  spread_from_file->restore(mine);
  for (Simulator<3>* sim : {one.get(), spread.get(), spread_resumed.get(), spread_from_file.get()})
    sim->advance_to(3.0);
  const std::vector<double> expected = raw_state(one->particles());
  EXPECT_GT(one->stats().contacts, 10);
  expect_whole_on_rank0(expected, raw_state(spread->particles()), "the run over ranks");
  expect_whole_on_rank0(expected, raw_state(spread_resumed->particles()),
                        "resumed over ranks from one rank's checkpoint");
  expect_whole_on_rank0(expected, raw_state(spread_from_file->particles()),
                        "resumed over ranks, each rank from its share of the file");
  if (on_rank0()) {
    auto one_resumed = dem::make_dem_simulator<3>(scene);
    one_resumed->restore(joined);
    one_resumed->advance_to(3.0);
    EXPECT_EQ(expected, raw_state(one_resumed->particles()))
        << "resumed on one rank from the checkpoint over ranks";
  }
  for (Simulator<3>* sim : {spread_resumed.get(), spread_from_file.get()}) {
    EXPECT_EQ(energies(one->energy()), energies(sim->energy()));
    EXPECT_EQ(one->stats().particle_steps, sim->stats().particle_steps);
    EXPECT_EQ(one->stats().contacts, sim->stats().contacts);
  }
}

}  // namespace
}  // namespace granjet

int main(int argc, char** argv) {
  granjet::MpiSession mpi;
  testing::InitGoogleTest(&argc, argv);
  // One report, from rank 0: the others' results reach it through the comparisons' exit codes.
  if (granjet::RankTeam::world().rank() != 0)
    delete testing::UnitTest::GetInstance()->listeners().Release(
        testing::UnitTest::GetInstance()->listeners().default_result_printer());
  return RUN_ALL_TESTS();
}
