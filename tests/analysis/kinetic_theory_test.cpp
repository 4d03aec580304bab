// Kinetic theory against values worked out by hand (the arithmetic is in the comments).
#include "analysis/kinetic_theory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace granjet::analysis::kinetic {
namespace {

TEST(KineticTheory, Eq5_3_ChiBothBranchesAndContinuityAtFreezing) {
  // Dilute branch: (1 - 0.15)/(0.7^3) = 0.85/0.343.
  EXPECT_NEAR(chi(0.3), 0.85 / 0.343, 1e-12);
  // Dense branch at 0.55: 0.755 * 0.15 / (0.51^3 * 0.09) = 0.11325/0.011938... = 9.48604.
  EXPECT_NEAR(chi(0.55), 0.755 * 0.15 / (0.132651 * 0.09), 1e-9);
  // Both branches give 0.755/0.51^3 = 5.69163 at phi_f.
  EXPECT_NEAR(chi(kPhiFreezing - 1e-12), chi(kPhiFreezing), 1e-9);
  EXPECT_NEAR(chi(kPhiFreezing), 5.691627, 1e-6);
  EXPECT_TRUE(std::isinf(chi(kPhiClosePacking)));
}

TEST(KineticTheory, Eq5_2_PressureRatioAndDirectionalForm) {
  // 1 + 2 * 0.3 * 1.75 * 2.478134 = 3.602041.
  EXPECT_NEAR(pressure_ratio(0.3, 0.75), 3.602041, 1e-6);
  EXPECT_NEAR(pressure_ratio(0.0, 0.75), 1.0, 1e-15);  // ideal gas
  // P_alpha = n T_alpha (1 + 2 phi (1+e) chi): n = 0.5, T_alpha = 0.2.
  EXPECT_NEAR(directional_pressure(0.5, 0.2, 0.3, 0.75), 0.1 * 3.602041, 1e-7);
}

TEST(KineticTheory, Eq2_55_EffectiveRestitutionIsSpecValue) {
  // 0.75 - 0.314159 + 0.18 = 0.615841; the model quotes 0.616.
  EXPECT_NEAR(effective_restitution(0.75, 0.2), 0.616, 5e-4);
  EXPECT_DOUBLE_EQ(effective_restitution(0.75, 0.0), 0.75);
}

TEST(KineticTheory, Eq2_37_SonineA2AndItsDDimensionalForm) {
  // e = 0.5: 16 * 0.5 * 0.5 / (81 - 8.5 + 3.75) = 4/76.25.
  EXPECT_NEAR(sonine_a2(0.5), 4.0 / 76.25, 1e-15);
  // van Noije & Ernst at d = 3 is [2.37] for every e.
  for (double e : {0.1, 0.5, 0.75, 0.9, 0.99}) EXPECT_NEAR(sonine_a2(e, 3), sonine_a2(e), 1e-15);
  // d = 2, e = 0.5: 4 / (9 + 48 - 0.5 * 25 + 3.75) = 4/48.25.
  EXPECT_NEAR(sonine_a2(0.5, 2), 4.0 / 48.25, 1e-15);
  EXPECT_DOUBLE_EQ(sonine_a2(1.0), 0.0);  // elastic: Maxwellian
}

TEST(KineticTheory, HaffCoolingPerCollision) {
  // Elastic grains do not cool; without the a2 correction the rate is -(1-e^2)/d.
  EXPECT_DOUBLE_EQ(cooling_per_collision(1.0, 3), 0.0);
  // e = 0.75, d = 3: a2 = -0.0068995, -(0.4375/3)(1 - 0.0012937)/(1 + 0.00043122) = -0.145582.
  EXPECT_NEAR(cooling_per_collision(0.75, 3), -0.145582, 1e-6);
  // d = 2: a2 = -0.0117734, -(0.4375/2)(1 - 0.0022075)/(1 + 0.00073584) = -0.218107.
  EXPECT_NEAR(cooling_per_collision(0.75, 2), -0.218107, 1e-6);
}

TEST(KineticTheory, CarnahanStarlingAndHenderson) {
  // phi = 0.5: (1 + 0.5 + 0.25 - 0.125)/0.125 = 13; (1 + 0.25/8)/0.25 = 4.125.
  EXPECT_NEAR(carnahan_starling(0.5), 13.0, 1e-12);
  EXPECT_NEAR(henderson(0.5), 4.125, 1e-12);
  EXPECT_DOUBLE_EQ(carnahan_starling(0.0), 1.0);
  EXPECT_DOUBLE_EQ(henderson(0.0), 1.0);
  // Carnahan-Starling is 1 + 4 phi g(phi) with [5.3]'s dilute chi: the same theory.
  EXPECT_NEAR(carnahan_starling(0.3), 1.0 + 4.0 * 0.3 * chi(0.3), 1e-12);
}

TEST(KineticTheory, EnskogCollisionFrequency) {
  // 3D: 4 sqrt(pi) n chi sqrt(T), n = phi / (pi/6), chi = (1 - phi/2)/(1 - phi)^3
  // (Carnahan-Starling); 2D: 2 sqrt(pi) n chi sqrt(T), n = phi / (pi/4),
  // chi = (1 - 7 phi/16)/(1 - phi)^2 (Henderson).
  const double phi = 0.3, t = 2.0, root_pi = std::sqrt(std::numbers::pi);
  const double n3 = phi / (std::numbers::pi / 6.0),
               chi3 = (1.0 - phi / 2.0) / std::pow(1.0 - phi, 3);
  EXPECT_NEAR(enskog_collision_frequency(phi, t, 3), 4.0 * root_pi * n3 * chi3 * std::sqrt(t),
              1e-12);
  const double n2 = phi / (std::numbers::pi / 4.0),
               chi2 = (1.0 - 7.0 * phi / 16.0) / std::pow(1.0 - phi, 2);
  EXPECT_NEAR(enskog_collision_frequency(phi, t, 2), 2.0 * root_pi * n2 * chi2 * std::sqrt(t),
              1e-12);
  // Dilute: chi -> 1 + 5 phi/2, so the Boltzmann frequency 24 phi sqrt(T/pi) within 0.25%.
  EXPECT_NEAR(enskog_collision_frequency(1e-3, 1.0, 3) / (24e-3 / root_pi), 1.0025, 1e-5);
}

TEST(KineticTheory, Eq5_4_to_5_11_GarzoDuftyViscosity) {
  // Elastic dilute limit: eta* -> 1 (c* = 0, nu = chi = 1, zeta = 0, gamma = 0).
  EXPECT_NEAR(viscosity_star(1e-9, 1.0), 1.0, 1e-7);
  // e = 0.75, phi = 0.3: chi = 2.478134, c* = -0.013799, nu = 2.478134 * 0.984375 * 1.000216
  // = 2.439939, zeta = 5/12 * 2.478134 * 0.4375 * 0.998706 = 0.451159, eta_k* =
  // (1 + 4.375 * 0.3 * 2.478134/5)/(2.439939 - 0.225579) = 1.650510/2.214360 = 0.745367,
  // gamma* = 8.148733 * 0.09 * 2.478134 * 1.75 * 1.000431 = 3.181872,
  // eta* = 0.745367 * (1 + 4 * 0.3 * 2.478134 * 1.75/5) + 0.6 * 3.181872
  //      = 0.745367 * 2.040816 + 1.909123 = 3.430280.
  EXPECT_NEAR(viscosity_star(0.3, 0.75), 3.430280, 2e-6);
  // [5.4]: eta_kin = 5/16 sqrt(T/pi) eta* for m = d = 1, T = 0.2: 0.078848 * 3.430280.
  EXPECT_NEAR(kinetic_viscosity(0.3, 0.75, 0.2, 1.0, 1.0), 0.270470, 2e-6);
  // Dilute viscosity, general D formula: 2D 1/(2d) sqrt(mT/pi).
  EXPECT_NEAR(dilute_viscosity(0.2, 1.0, 1.0, 2), 0.5 * std::sqrt(0.2 / std::numbers::pi), 1e-15);
}

}  // namespace
}  // namespace granjet::analysis::kinetic
