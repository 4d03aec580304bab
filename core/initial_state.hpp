// Builds the initial grains of a scene [model §4-§5]: the jet lattice with random site removal,
// the target wall layer, the two grains of the binary scene, or a periodic gas.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/particles.hpp"
#include "core/scene.hpp"

namespace granjet {

// The periodic box of a gas scene and its starting lattice, fcc (3D) or triangular (2D):
// `cells` unit cells of edges `cell_edge` per axis fill the box, with at least gas.grains sites
// of which gas.grains are kept at random. The box holds the grains at exactly gas.phi.
template <int D>
struct GasLattice {
  std::array<int, D> cells{};
  Vec<D> cell_edge = Vec<D>::Zero();
  Vec<D> box = Vec<D>::Zero();
  double nearest = 0.0;  // nearest-neighbour distance of the lattice sites
};

template <int D>
GasLattice<D> gas_lattice(const GasSpec& gas);

extern template GasLattice<2> gas_lattice<2>(const GasSpec&);
extern template GasLattice<3> gas_lattice<3>(const GasSpec&);

// Which of a scene's grains one of `parts` MPI ranks builds, so that no rank holds the whole
// run: of the jet's N grains (or the binary scene's, or a gas's) ids [N part / parts,
// N (part + 1) / parts), and every target grain (the target is small, and each rank ties the
// same springs from the whole of it). The grains come out the same as the whole state's.
struct GrainShare {
  int part = 0;
  int parts = 1;
  bool holds(std::int64_t index, std::int64_t of) const {
    return index >= of * part / parts && index < of * (part + 1) / parts;
  }
};

// The jet travels along -e_z (3D) or -e_x (2D) towards target grains centred in the plane
// z = 0 (x = 0). Jet grains get ids 0..N-1, wall grains N.. . Tethered wall grains have mass
// m, fixed ones infinite mass (inverse mass 0). Gas grains (ids 0..N-1 in lattice order) sit in
// [0, box) with Maxwellian velocities of zero total momentum and exactly gas.temperature.
// Grains come in id order.
template <int D>
Particles<D> build_initial_state(const Scene& scene, GrainShare share = {});

// A grain's mass, for the initial state and for anything that rebuilds grains from a file: jet
// (and gas, binary) grains m = 1, or diameter^D with jet.mass_by_volume; target grains m = 1,
// infinite (immovable) when wall.kind = fixed.
template <int D>
double grain_mass(const Scene& scene, GrainKind kind, double diameter) {
  if (kind == GrainKind::kWall)
    return scene.wall.kind == WallKind::kFixed ? std::numeric_limits<double>::infinity() : 1.0;
  return scene.jet.mass_by_volume ? std::pow(diameter, D) : 1.0;
}

// Sizes of a scene's initial state before it is built (run budgets, plans), where building it
// could take a day: the jet column's length along its axis (jet.grains / jet.phi_tilde lattice
// sites at the lattice's volume per site, fcc s^3/sqrt 2 or triangular s^2 sqrt(3)/2, over the
// cross section), the target grains (the row's count in 2D, the disk's area over a site's area
// in 3D) and the periodic box's edge (gas.grains at gas.phi).
double jet_column_length(const Scene& scene);
double target_grains_estimate(const Scene& scene);
double gas_box_edge(const Scene& scene);

extern template Particles<2> build_initial_state<2>(const Scene&, GrainShare);
extern template Particles<3> build_initial_state<3>(const Scene&, GrainShare);

}  // namespace granjet
