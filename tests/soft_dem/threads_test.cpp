// run.threads changes nothing but the speed: the shared force pass (contacts evaluated apart,
// then every grain sums its own in list order) gives the serial results bit for bit, with
// friction and rotation, both integrators, a tethered wall, the plate and a periodic box.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../common/raw_state.hpp"
#include "run/scene_file.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet {
namespace {

// Every grain's state by id, as raw doubles.
template <int D>
std::vector<double> state_by_id(const Simulator<D>& sim) {
  const Particles<D>& p = sim.particles();
  std::vector<double> out;
  std::vector<std::size_t> index(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) index[i] = i;
  std::sort(index.begin(), index.end(), [&](auto a, auto b) { return p.id()[a] < p.id()[b]; });
  for (std::size_t i : index) testing::append_raw_state(out, p, i);
  return out;
}

template <int D>
void expect_thread_count_invariant(const std::string& scene_file, std::vector<std::string> set,
                                   double t_end, std::vector<int> thread_counts = {1, 2}) {
  std::vector<std::vector<double>> states;
  for (int threads : thread_counts) {
    std::vector<std::string> overrides = set;
    overrides.push_back("run.threads=" + std::to_string(threads));
    const Scene scene = load_scene(std::string(GRANJET_SCENES_DIR) + "/" + scene_file, overrides);
    auto sim = dem::make_dem_simulator<D>(scene);
    sim->advance_to(t_end);
    EXPECT_GT(sim->stats().contacts, 10);
    states.push_back(state_by_id(*sim));
  }
  for (std::size_t k = 1; k < states.size(); ++k)
    EXPECT_EQ(states[0], states[k]) << thread_counts[k] << " threads";  // every double exactly
}

TEST(Threads, Jet2dFrictionalBidisperseAb2IsBitIdentical) {
  expect_thread_count_invariant<2>("jet2d.ini", {"jet.grains=1500", "contact.friction=0.5"}, 3.0);
}

TEST(Threads, Jet3dFrictionalVerletIsBitIdentical) {
  expect_thread_count_invariant<3>(
      "jet3d.ini", {"jet.grains=2000", "run.integrator=verlet", "wall.diameter=14"}, 3.0);
}

TEST(Threads, Jet2dOnTheFrictionalPlateIsBitIdentical) {
  expect_thread_count_invariant<2>(
      "jet2d.ini", {"jet.grains=1500", "contact.friction=0.5", "wall.kind=plate"}, 3.0);
}

TEST(Threads, Jet3dWithRollingResistanceOnThePlateIsBitIdentical) {
  expect_thread_count_invariant<3>(
      "jet3d.ini",
      {"jet.grains=2000", "contact.rolling_friction=0.1", "wall.kind=plate", "wall.diameter=14"},
      3.0);
}

// Many threads on a larger jet: stretches short against the span of the pairs, so that a
// stretch's contacts reach the grains of several later threads, and threads left without
// contacts before the impact.
TEST(Threads, Jet3dOnManyThreadsIsBitIdentical) {
  expect_thread_count_invariant<3>("jet3d.ini", {"jet.grains=6000", "wall.diameter=20"}, 4.0,
                                   {1, 5, 16});
}

TEST(Threads, PeriodicGasIsBitIdentical) {
  expect_thread_count_invariant<3>("hcs3d.ini", {"gas.grains=864", "gas.phi=0.3"}, 2.0,
                                   {1, 2, 3});  // uneven shares of the rows
}

}  // namespace
}  // namespace granjet
