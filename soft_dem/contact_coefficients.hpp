// Linear spring-dashpot coefficients from the scene's (e, t_c) [3.4]-[3.5].
#pragma once

#include <limits>

#include "core/scene.hpp"

namespace granjet::dem {

// All in the model's units (d, m, u0). The dashpots are rates: the damping force is
// m * eta * (overlap rate) with m the grain mass unit, whatever the partner [model §2].
struct ContactCoefficients {
  double kn = 0.0;     // normal spring k_n
  double eta_n = 0.0;  // normal dashpot rate
  double kt = 0.0;     // tangential spring k_t = spring_ratio k_n
  double eta_t = 0.0;  // tangential dashpot rate eta_t = damping_ratio eta_n
  double mu = 0.0;     // Coulomb friction mu_p
  // The least normal force: -infinity (the linear law of [3.1], attraction allowed) or 0
  // (contact.clamp_normal). A floor, so the unclamped law is bit for bit the plain one.
  double normal_floor = -std::numeric_limits<double>::infinity();
  double adhesion = 0.0;  // F_a (adhesion.hpp), the same for a pair and against the plate
};

// [3.4] t_c = pi / sqrt(2 k_n/m - eta_n^2) and [3.5] e = exp(-t_c eta_n), for two grains of
// mass m = 1, solved for (k_n, eta_n).
ContactCoefficients contact_coefficients(const ContactSpec& spec);

// The other way: the head-on collision (e, t_c) of two unit grains that a given (k_n, eta_n)
// gives by [3.4]-[3.5]; NaN when the dashpot is overdamped (2 k_n <= eta_n^2: no rebound).
struct BinaryCollision {
  double restitution = 0.0;
  double contact_time = 0.0;
};
BinaryCollision binary_collision(double kn, double eta_n);

}  // namespace granjet::dem
