// Spec §7b: the free-streamline (Kirchhoff-Helmholtz) solution of an ideal-fluid 2D jet of full
// width 2R and speed U hitting, normally, a flat plate of full width 2L: the exact answer that
// the hard-core question's plate runs are compared with. Lengths in units of R, forces in units
// of rho U^2 R (per unit depth).
#pragma once

namespace granjet::analysis::free_streamline {

// L/R of the plate whose exit sheets leave at psi0 (radians from the incoming direction,
// 0 < psi0 < pi/2): (1/pi) * integral_1^a dt / (t chi(t)), a = 1/cos^2 psi0 [model §7b].
double plate_half_width(double psi0);

// The exit angle psi0 (radians) for a plate of half-width L/R > 0: plate_half_width inverted.
// psi0 -> 0 as L/R -> 0 and -> pi/2 as L/R grows without bound.
double exit_angle(double plate_over_jet);

// The force on the plate by momentum balance: 2 (1 - cos psi0) (rho U^2 R).
double momentum_force(double psi0);

// The same force as the Bernoulli pressure integral over the plate:
// (1/pi) * integral_1^a (1 - chi^2) / (t chi) dt (rho U^2 R).
double pressure_force(double psi0);

// chi(t) = |dw/dz|/U on the plate, 0 at the stagnation point t = 1, 1 at the edge t = a.
double hodograph(double t, double psi0);

}  // namespace granjet::analysis::free_streamline
