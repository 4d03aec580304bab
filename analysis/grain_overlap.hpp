// How much of one grain lies inside a bin, for the packing fraction phi (model §6: the exact grain
// volume or area inside the bin, not centre counting).
#pragma once

namespace granjet::analysis {

// Area of the disk (centre cx, cy; radius r) inside the rectangle [x0, x1] x [y0, y1]. Exact:
// the chord length inside the rectangle is integrated in closed form between its kinks.
double disk_rectangle_area(double cx, double cy, double r, double x0, double x1, double y0,
                           double y1);

// Area common to two disks of radii a and b whose centres are c apart. Exact.
double lens_area(double a, double b, double c);

// Volume of the sphere of radius r, centred at distance rho from the z axis and at height zc,
// inside the cylinder of radius `cylinder` about the z axis and between the planes z0 <= z1.
// The cross-section at height z is a disk of radius sqrt(r^2 - (z-zc)^2), so the volume is the
// integral of its lens with the cylinder's cross-section: Gauss-Legendre in the polar angle of
// the sphere, split where the lens changes form (tangencies), so each piece is smooth. Exact when
// the sphere is wholly inside or outside the cylinder; otherwise within 1e-6 of the sphere's
// volume (tested against a fine midpoint rule and the coaxial closed form).
double sphere_cylinder_slab_volume(double rho, double zc, double r, double cylinder, double z0,
                                   double z1);

}  // namespace granjet::analysis
