// Simulator::travel in the soft DEM: the sum of each step's dt times its largest speed, carried
// over the neighbour rebuilds, so that between two reads it bounds every grain's displacement.
// The inline analysis relies on it to ask a run over ranks for the newly scattered grains only.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <map>
#include <string>

#include "run/backend_factory.hpp"
#include "run/scene_file.hpp"

namespace granjet {
namespace {

std::map<GrainId, Vec<3>> positions_by_id(const Simulator<3>& sim) {
  const Particles<3>& p = sim.particles();
  std::map<GrainId, Vec<3>> at;
  for (std::size_t i = 0; i < p.size(); ++i) at[p.id()[i]] = p.position()[i];
  return at;
}

void expect_travel_bounds_displacements(const std::string& integrator) {
  const Scene jet = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini",
                               {"jet.grains=800", "run.t_end=8", "run.integrator=" + integrator});
  const auto sim = make_simulator<3>("soft_dem", jet);
  sim->advance_to(3.0);  // the impact: grains pushed, slowed and sent sideways
  const std::map<GrainId, Vec<3>> before = positions_by_id(*sim);
  const double travel_before = sim->travel();
  const std::int64_t rebuilds_before = sim->stats().neighbour_rebuilds;
  sim->advance_to(6.0);
  ASSERT_GT(sim->stats().neighbour_rebuilds, rebuilds_before + 2);  // the bound spans lists
  double farthest = 0.0;
  for (const auto& [id, x] : positions_by_id(*sim))
    if (before.contains(id)) farthest = std::max(farthest, (x - before.at(id)).norm());
  const double travel = sim->travel() - travel_before;
  EXPECT_LE(farthest, travel) << integrator;
  // A bound by the fastest grain: the jet flies at u0 = 1, so about the time elapsed.
  EXPECT_GT(farthest, 0.5 * travel) << integrator;
  EXPECT_LT(travel, 3.0 * 1.5) << integrator;
}

TEST(Travel, BoundsEveryGrainsDisplacementAcrossRebuilds) {
  expect_travel_bounds_displacements("ab2");
  expect_travel_bounds_displacements("verlet");
}

TEST(Travel, IsUnknownToTheEventDrivenBackend) {
  const Scene jet = load_scene(std::string(GRANJET_SCENES_DIR) + "/jet3d.ini", {"jet.grains=200"});
  EXPECT_EQ(make_simulator<3>("event_driven", jet)->travel(),
            std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace granjet
