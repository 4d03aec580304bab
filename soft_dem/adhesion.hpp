// Adhesion, an optional part of a soft contact law (contact.adhesion = F_a >= 0; not in the
// study): a constant pull F_a between touching surfaces, added to the law's normal force,
//   F_n = F_law - F_a   while the grains overlap (nothing once they part),
// the adhesion of the DMT model (Derjaguin, Muller & Toporov, J. Colloid Interface Sci. 53,
// 314 (1975)), as in LAMMPS's `pair granular ... dmt`, where F_a = 4 pi gamma R*. granjet takes
// the force itself, the same for every pair and against the plate (the study's grains differ
// in size by 20% at most). Its potential is -F_a delta, so a resting pair settles where the
// law's repulsion balances it (delta = F_a / k_n for the linear law). The Coulomb limit is
// mu_p times the law's own |F_n| (DMT's pull-off adds no load on the asperities). Model §2,
// "Adhesion".
//
// A part every law takes in its normal force and its energy, with F_a = 0 for none: x - 0.0 is
// x exactly, so scenes without adhesion run bit for bit as before, with no template of their
// own.
#pragma once

namespace granjet::dem {

// The normal force along n (positive: repulsive) with the pull F_a.
inline double with_adhesion(double law_normal_force, double adhesion) {
  return law_normal_force - adhesion;
}

// The pull's potential energy at `overlap` (its work from first touch).
inline double adhesion_energy(double overlap, double adhesion) { return -adhesion * overlap; }

}  // namespace granjet::dem
