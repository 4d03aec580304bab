// Kinetic theory of inelastic hard spheres used as the reference for the measured fields
// (model §6, "Kinetic-theory comparisons"). Units: d, m, u0 (grain diameter and mass are
// arguments where the formulas need them, so the functions also work in other units).
#pragma once

namespace granjet::analysis::kinetic {

// Freezing and random-close-packing fractions of the two branches of [5.3].
constexpr double kPhiFreezing = 0.49;
constexpr double kPhiClosePacking = 0.64;

// [5.3] pair correlation at contact: Carnahan-Starling form below phi_f, the branch diverging at
// phi_c above. Infinite at and beyond phi_c.
double chi(double phi);
// [5.2] P/(n T_g) = 1 + 2 phi (1+e) chi; the same ratio gives the directional equation of state
// P_alpha/(n T_alpha) (model §6).
double pressure_ratio(double phi, double e);
// Directional form of [5.2]: P_alpha = n T_alpha (1 + 2 phi (1+e) chi).
double directional_pressure(double n, double t_alpha, double phi, double e);
// [2.55] effective restitution of frictional grains: e - (pi/2) mu_p + (9/2) mu_p^2.
double effective_restitution(double e, double mu_p);

// [2.37] Sonine coefficient of the homogeneous cooling state in 3D.
double sonine_a2(double e);
// The same in `dimension` dimensions (van Noije & Ernst, Granular Matter 1, 57 (1998)):
// a2 = 16(1-e)(1-2e^2) / (9 + 24d - e(41 - 8d) + 30(1-e)e^2); d = 3 gives [2.37].
double sonine_a2(double e, int dimension);
// Haff cooling per collision: d ln T / d(collisions per grain)
//   = -(1-e^2)/d (1 + 3 a2/16) / (1 - a2/16),
// the cooling rate's factor (1 + 3a2/16) over the collision frequency's (1 - a2/16) (van Noije &
// Ernst 1998), with the d-dimensional a2: to leading order each collision dissipates (1-e^2) T
// and each grain holds D T/2.
double cooling_per_collision(double e, int dimension);

// Compressibility factors P/(n T) of elastic hard spheres (Carnahan-Starling) and hard disks
// (Henderson).
double carnahan_starling(double phi);
double henderson(double phi);
// Enskog's collision frequency per grain of elastic hard spheres (disks) of unit diameter and
// mass at temperature T: 4 sqrt(pi) n chi sqrt(T) in 3D, 2 sqrt(pi) n chi sqrt(T) in 2D, n the
// number density, with the contact value chi that makes the equation of state above exact
// (Z = 1 + 2^(D-1) phi chi): 24 phi chi sqrt(T/pi) and 8 phi chi sqrt(T/pi).
double enskog_collision_frequency(double phi, double temperature, int dimension);

// [5.4]-[5.11] Garzo-Dufty dimensionless shear viscosity eta*(phi, e) of inelastic hard spheres
// (the curve [5.6] of figure F5.9).
double viscosity_star(double phi, double e);
// Dilute (Boltzmann) shear viscosity of elastic hard spheres (dimension 3, the prefactor of
// [5.4]: 5/(16 d^2) sqrt(m T/pi)) or hard disks (dimension 2: 1/(2 d) sqrt(m T/pi)); both are
// (D+2) Gamma(D/2) / (8 pi^((D-1)/2)) sqrt(m T) / d^(D-1) (Garzo & Dufty, PRE 59, 5895 (1999)).
// The measured eta* is eta over this.
double dilute_viscosity(double temperature, double mass, double diameter, int dimension);
// [5.4] eta_kin = 5/(16 d^2) sqrt(m T_g/pi) eta*(phi).
double kinetic_viscosity(double phi, double e, double temperature, double mass, double diameter);

}  // namespace granjet::analysis::kinetic
