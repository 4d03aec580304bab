// Stability (e): long elastic runs, energy drift.
//
// Soft DEM, e = 1 (eta_n = 0 by [3.5]), frictionless, at the study's dt = 0.02 t_c: the 2D jet
// (bidisperse, 2000 grains, strip 20 d) against a fixed target, t = 0 ... 100 = 1000 contact
// times (50,000 steps), for AB2 [B.21]-[B.24] and velocity Verlet. Nothing dissipates, so the
// energy balance's "dissipated" (initial energy minus kinetic, elastic and removed) is the
// integrator's energy error; its relative drift is recorded every 10 d/u0.
// Expected: the drift stays below 1% of E_0 over the whole run for both (an error that size
// is small beside what e = 0.75 dissipates, tens of percent). Velocity Verlet is symplectic for
// this conservative force, AB2 is not: Verlet's drift should be the smaller.
//
// Event-driven, the elastic 3D gas (scenes/gas3d.ini: 10,976 spheres, phi = 0.3) over 10^7
// collisions, drift recorded every 10^6. Expected: below 1e-9 relative (collisions conserve
// energy exactly but for rounding), as the default suite demands over 10^6.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "event_driven/ed_simulator.hpp"
#include "soft_dem/dem_simulator.hpp"
#include "stability_common.hpp"

namespace granjet::stability {
namespace {

double elastic_jet_drift(const std::string& integrator) {
  const Scene scene = shipped_scene(
      "jet2d", {"run.integrator=" + integrator, "contact.restitution=1", "wall.kind=fixed",
                "jet.diameter=20", "wall.diameter=44", "region.radius=88", "jet.grains=2000",
                "run.t_end=100", "analysis.enabled=false"});
  Stopwatch clock;
  auto sim = dem::make_dem_simulator<2>(scene);
  const double e0 = sim->energy().total();
  std::string series;
  double worst = 0.0, drift = 0.0;
  for (double t = 10.0; t <= scene.run.t_end + 1e-9; t += 10.0) {
    sim->advance_to(t);
    drift = -sim->energy().dissipated / e0;
    worst = std::max(worst, std::abs(drift));
    series += cat(" t", t, ": ", drift);
  }
  report("drift.soft_dem." + integrator,
         cat("relative energy drift", series, "; largest |drift| ", worst, ", ", sim->stats().steps,
             " steps, ", sim->stats().removed, " grains removed, ", clock.seconds(), " s"));
  EXPECT_TRUE(all_finite(sim->particles()));
  EXPECT_LT(worst, 0.01) << integrator;
  return worst;
}

TEST(EnergyDrift, B21_ElasticJetOverAThousandContactTimesBothIntegrators) {
  const double ab2 = elastic_jet_drift("ab2");
  const double verlet = elastic_jet_drift("verlet");
  EXPECT_LT(verlet, ab2) << "velocity Verlet (symplectic) should drift less than AB2";
}

TEST(EnergyDrift, Sec8_ElasticGasOverTenMillionCollisions) {
  const Scene scene = shipped_scene("gas3d", {"gas.equilibration=0", "run.t_end=1e9"});
  Watchdog dog(300.0, "drift.event_driven");
  Stopwatch clock;
  auto sim = ed::make_ed_simulator<3>(scene);
  const double e0 = sim->energy().kinetic;
  std::string series;
  double worst = 0.0;
  std::int64_t next = 1'000'000;
  while (sim->stats().collisions < 10'000'000) {
    sim->advance_to(sim->time() + 0.5);  // about 28,000 collisions
    if (sim->stats().collisions >= next) {
      const double drift = sim->energy().kinetic / e0 - 1.0;
      worst = std::max(worst, std::abs(drift));
      series += cat(" ", sim->stats().collisions / 1'000'000, "e6: ", drift);
      next += 1'000'000;
    }
  }
  const double drift = sim->energy().kinetic / e0 - 1.0;
  worst = std::max(worst, std::abs(drift));
  report("drift.event_driven.gas3d",
         cat(sim->stats().collisions, " collisions, t = ", sim->time(), ", relative energy drift",
             series, "; largest |drift| ", worst, ", ", sim->stats().collisions / clock.seconds(),
             " collisions/s, ", clock.seconds(), " s"));
  EXPECT_TRUE(all_finite(sim->particles()));
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace granjet::stability
