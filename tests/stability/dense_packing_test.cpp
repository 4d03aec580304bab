// Stability (c): dense packings near jamming.
//
// Soft DEM, at the study's dt = 0.02 t_c [model §3]: compact jets whose grains touch from the
// start, so the region over the target jams into a packing of many persistent contacts:
// - 2D: monodisperse disks on a triangular lattice of spacing 1.0 d with every site kept
//   (phi = 0.907, the close packing), mu_p = 0.2, tethered target;
// - 3D: the jet3d fcc (spacing 1.0 d, phi~0 = 0.9, phi = 0.67), D_jet = 6 d, mu_p = 0.2.
// Expected: no blow-up; the largest overlap, measured independently of the backend's own check,
// stays within run.max_overlap of the smaller radius (a u0 impact gives about u0 t_c / pi =
// 0.03 d); the energy balance closes: the dissipated energy (initial energy minus kinetic,
// rotational, elastic and removed) never decreases by more than 1e-4 E_0 between samples
// (dashpots and Coulomb sliding only take energy out; the integrator's error is far smaller).
//
// Event-driven, dense periodic gases near their densest lattice (2D phi = 0.8, 3D phi = 0.6):
// elastic, velocity-dependent e0 = 0.75 and constant e0 = 0.75, each to 200 collisions per
// grain. Expected: each run either gets there or stops with a clear inelastic-collapse
// BlowUpError (only the constant law may), without hanging (a watchdog ends the executable
// after 120 s).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/errors.hpp"
#include "event_driven/ed_simulator.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "stability_common.hpp"

namespace granjet::stability {
namespace {

struct DenseJet {
  std::string name;
  int dimension;
  std::vector<std::string> overrides;
};

template <int D>
void run_dense_jet(const DenseJet& c) {
  const Scene scene = shipped_scene(D == 2 ? "jet2d" : "jet3d", c.overrides);
  Stopwatch clock;
  auto sim = dem::make_dem_simulator<D>(scene);
  const double e0 = sim->energy().total();
  double dissipated = 0.0, worst_drop = 0.0, worst_overlap = 0.0;
  std::int64_t most_contacts = 0;
  double contacts_per_grain = 0.0;
  try {
    for (double t = 0.5; t <= scene.run.t_end + 1e-9; t += 0.5) {
      sim->advance_to(t);
      const EnergyBalance b = sim->energy();
      worst_drop = std::max(worst_drop, (dissipated - b.dissipated) / e0);
      dissipated = b.dissipated;
      worst_overlap = std::max(worst_overlap, max_overlap_fraction(sim->particles()));
      if (sim->stats().contacts > most_contacts) {
        most_contacts = sim->stats().contacts;
        contacts_per_grain = 2.0 * most_contacts / static_cast<double>(sim->particles().size());
      }
    }
  } catch (const BlowUpError& e) {
    ADD_FAILURE() << c.name << ": " << e.what();
  }
  report("dense." + c.name,
         cat(sim->particles().size(), " grains at the end, up to ", most_contacts, " contacts (",
             contacts_per_grain, " per grain), max overlap ", worst_overlap,
             " of the smaller radius (limit ", scene.run.max_overlap, "), dissipated ",
             dissipated / e0, " E_0, largest drop of the dissipated energy ", worst_drop, " E_0, ",
             sim->stats().steps, " steps, ", clock.seconds(), " s"));
  EXPECT_TRUE(all_finite(sim->particles()));
  EXPECT_LT(worst_overlap, scene.run.max_overlap);
  EXPECT_LT(worst_drop, 1e-4);
  EXPECT_GT(dissipated, 0.0);
}

TEST(DensePacking, Sec3_JammedJet2dCloselyPackedStaysStableAtTheStudyDt) {
  run_dense_jet<2>({"jet2d_close_packed",
                    2,
                    {"jet.dispersity=mono", "jet.spacing=1.0", "jet.phi_tilde=1.0",
                     "jet.diameter=20", "wall.diameter=44", "region.radius=88", "jet.grains=3000",
                     "contact.friction=0.2", "run.t_end=60", "analysis.enabled=false"}});
}

TEST(DensePacking, Sec3_JammedJet3dFccStaysStableAtTheStudyDt) {
  run_dense_jet<3>({"jet3d_fcc",
                    3,
                    {"jet.diameter=6", "wall.diameter=14", "region.radius=28", "jet.grains=3000",
                     "run.t_end=40", "analysis.enabled=false"}});
}

struct DenseGas {
  int dimension;
  double phi;
  std::int64_t grains;
};

class DenseEdGas : public ::testing::TestWithParam<DenseGas> {};

template <int D>
void run_dense_gas(const DenseGas& c) {
  struct Law {
    const char* name;
    double e;
    const char* law;
  };
  for (const Law& law : {Law{"elastic", 1.0, "constant"},
                         Law{"velocity_dependent_e0.75", 0.75, "velocity_dependent"},
                         Law{"constant_e0.75", 0.75, "constant"}}) {
    const std::string key = cat("dense_ed.", D, "d.phi", c.phi, ".", law.name);
    Watchdog dog(120.0, key);
    const Scene scene = shipped_scene(
        D == 2 ? "gas2d" : "gas3d",
        {"scene.kind=" + std::string(law.e < 1.0 ? "hcs" : "gas"),
         "contact.restitution=" + std::to_string(law.e),
         std::string("ed.restitution_law=") + law.law, "gas.phi=" + std::to_string(c.phi),
         "gas.grains=" + std::to_string(c.grains), "gas.equilibration=0", "run.t_end=1e9"});
    Stopwatch clock;
    auto sim = ed::make_ed_simulator<D>(scene);
    const double n = static_cast<double>(sim->particles().size());
    const double e0 = sim->energy().kinetic;
    std::string outcome = "ran to the budget";
    bool collapsed = false;
    double chunk = 0.01;
    try {
      // (A cooling gas that froze below 1e-30 T_0 would never get there: stop.)
      while (2.0 * sim->stats().collisions / n < 200.0 && sim->energy().kinetic > 1e-30 * e0) {
        const std::int64_t before = sim->stats().collisions;
        sim->advance_to(sim->time() + chunk);
        if (2.0 * (sim->stats().collisions - before) / n < 10.0) chunk *= 2.0;
      }
    } catch (const BlowUpError& e) {
      collapsed = true;
      outcome = e.what();
      EXPECT_NE(outcome.find("inelastic collapse"), std::string::npos) << outcome;
      EXPECT_GE(e.grain_ids().size(), 2u);
    }
    const double seconds = clock.seconds();
    report(key, cat(2.0 * sim->stats().collisions / n, " collisions/grain, t = ", sim->time(),
                    ", T/T0 = ", sim->energy().kinetic / e0, ", ",
                    sim->stats().collisions / seconds, " collisions/s; ", outcome));
    EXPECT_TRUE(all_finite(sim->particles()));
    if (law.e == 1.0 || std::string(law.law) != "constant") {
      EXPECT_FALSE(collapsed) << outcome;
    }
    if (law.e == 1.0) {
      EXPECT_NEAR(sim->energy().kinetic / e0, 1.0, 1e-9);
    }
  }
}

TEST_P(DenseEdGas, Sec8_RunsOrReportsCollapseWithoutHanging) {
  if (GetParam().dimension == 2)
    run_dense_gas<2>(GetParam());
  else
    run_dense_gas<3>(GetParam());
}

INSTANTIATE_TEST_SUITE_P(NearTheirDensestLattice, DenseEdGas,
                         ::testing::Values(DenseGas{2, 0.8, 2000}, DenseGas{3, 0.6, 2048}),
                         [](const auto& info) { return cat(info.param.dimension, "D"); });

}  // namespace
}  // namespace granjet::stability
