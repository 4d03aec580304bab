#include "core/initial_state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "core/jet_geometry.hpp"
#include "core/random.hpp"

namespace granjet {
namespace {

// Lattice neighbours placed exactly touching (spacing = 1 d, the smallest the scene file allows,
// as jet3d's fcc) are, in floating point, a coin flip between an overlap and a gap of ~1e-16 d:
// a third of them would start as contacts without force, and several thousand of those persist
// through the run (jet3d: 5,000 of 6,400 contacts at t = 10), each costing a full evaluation.
// Spreading such a jet by this relative amount parts them for good, far below any physical
// length; wider lattices are left as they are.
constexpr double kLatticeClearance = 1e-9;

// Whether (x, y) lies in the 3D jet's cross section [model §5]: the cylinder of diameter D_jet,
// or the rectangle of the anisotropy runs, long side along x, short side along y (JetSpec).
bool in_cross_section(const JetSpec& jet, double x, double y) {
  constexpr double kSlack = 1e-9;  // sites on the border belong to the jet
  if (jet.shape == JetShape::kRectangle)
    return std::abs(x) <= 0.5 * jet.long_side() + kSlack &&
           std::abs(y) <= 0.5 * jet.short_side() + kSlack;
  const double r_cut = 0.5 * jet.diameter;
  return x * x + y * y <= r_cut * r_cut + kSlack;
}

// Jet lattice sites come layer by layer away from the target; each survives the random removal
// with probability phi~0 [model §5], and the first N survivors make the jet. Only the share's
// survivors are kept (every site draws its number all the same).
// 3D: fcc with nearest-neighbour distance `spacing`, cut to the cross section.
std::vector<Vec<3>> jet_sites_3d(const JetSpec& jet, double front, Random& rng, GrainShare share) {
  const double a = std::sqrt(2.0) * jet.spacing;  // cube edge
  const int n_xy = static_cast<int>(jet.outer_radius() / a) + 2;
  // Each half cube layer holds two of the four fcc basis sites.
  constexpr std::array<std::array<double, 2>, 4> kBasis{
      {{0.0, 0.0}, {0.5, 0.5}, {0.5, 0.0}, {0.0, 0.5}}};
  std::vector<Vec<3>> sites;
  std::int64_t survivors = 0;
  for (int layer = 0; survivors < jet.grains; ++layer) {
    const int sub = layer % 2;
    const double z = front + a * (layer / 2 + 0.5 * sub);
    std::vector<std::pair<double, double>> xy;
    for (int i = -n_xy; i <= n_xy; ++i)
      for (int j = -n_xy; j <= n_xy; ++j)
        for (int b = 2 * sub; b < 2 * sub + 2; ++b) {
          const double x = a * (i + kBasis[b][0]), y = a * (j + kBasis[b][1]);
          if (in_cross_section(jet, x, y)) xy.emplace_back(x, y);
        }
    std::sort(xy.begin(), xy.end());
    for (const auto& [x, y] : xy) {
      if (rng.uniform() >= jet.phi_tilde) continue;
      if (share.holds(survivors, jet.grains)) sites.emplace_back(x, y, z);
      if (++survivors == jet.grains) break;
    }
  }
  return sites;
}

// 2D: triangular lattice of spacing `spacing`, rows across the strip |y| <= R_jet.
std::vector<Vec<2>> jet_sites_2d(const JetSpec& jet, double front, Random& rng, GrainShare share) {
  const double s = jet.spacing;
  const double row_height = s * std::sqrt(3.0) / 2.0;
  const double half_width = 0.5 * jet.diameter;
  const int n_y = static_cast<int>(half_width / s) + 2;
  std::vector<Vec<2>> sites;
  std::int64_t survivors = 0;
  for (int row = 0; survivors < jet.grains; ++row) {
    const double offset = 0.5 * s * (row % 2);
    for (int c = -n_y; c <= n_y; ++c) {
      const double y = c * s + offset;
      if (std::abs(y) > half_width + 1e-9 || rng.uniform() >= jet.phi_tilde) continue;
      if (share.holds(survivors, jet.grains)) sites.emplace_back(front + row * row_height, y);
      if (++survivors == jet.grains) break;
    }
  }
  return sites;
}

// Target grains [model §4]: one layer covering the disk of diameter D_tar in the plane z = 0
// (3D), or a row covering |y| <= R_tar on x = 0 (2D); neighbours wall.spacing apart (touching by
// default), on a hexagonal or square lattice (3D).
std::vector<Vec<3>> wall_sites_3d(const WallSpec& wall) {
  const double r_tar = 0.5 * wall.diameter;
  const bool hexagonal = wall.lattice == WallLattice::kHexagonal;
  const double row = hexagonal ? wall.spacing * std::sqrt(3.0) / 2.0 : wall.spacing;
  const int n_rows = static_cast<int>(r_tar / row) + 2;
  const int n_columns = static_cast<int>(r_tar / wall.spacing) + 2;
  std::vector<Vec<3>> sites;
  for (int r = -n_rows; r <= n_rows; ++r)
    for (int c = -n_columns; c <= n_columns; ++c) {
      const double shift = hexagonal ? 0.5 * ((r % 2 + 2) % 2) : 0.0;  // odd rows sit in gaps
      const double x = (c + shift) * wall.spacing;
      const double y = r * row;
      if (x * x + y * y <= r_tar * r_tar + 1e-9) sites.emplace_back(x, y, 0.0);
    }
  return sites;
}

std::vector<Vec<2>> wall_sites_2d(const WallSpec& wall) {
  const int n = static_cast<int>(std::floor(0.5 * wall.diameter / wall.spacing + 1e-9));
  std::vector<Vec<2>> sites;
  for (int c = -n; c <= n; ++c) sites.emplace_back(0.0, c * wall.spacing);
  return sites;
}

// A random layer: every site shifted within the target plane, uniformly over the disk (3D) or
// segment (2D) of radius wall.jitter. Its own random stream, so the jet's sites do not depend on
// whether the target is jittered.
template <int D>
void jitter_wall_sites(std::vector<Vec<D>>& sites, const WallSpec& wall, std::uint64_t seed) {
  if (wall.jitter <= 0.0) return;
  Random rng(seed ^ 0x9e3779b97f4a7c15ull);
  for (Vec<D>& x : sites) {
    if constexpr (D == 3) {
      const double radius = wall.jitter * std::sqrt(rng.uniform());
      const double angle = 2.0 * std::numbers::pi * rng.uniform();
      x[0] += radius * std::cos(angle);
      x[1] += radius * std::sin(angle);
    } else {
      x[1] += wall.jitter * (2.0 * rng.uniform() - 1.0);
    }
  }
}

// Grain diameters: all d (none listed), or exactly half d and half small_diameter in random
// order.
std::vector<double> jet_diameters(const JetSpec& jet, Random& rng) {
  if (jet.dispersity != Dispersity::kBi) return {};
  std::vector<double> diameters(jet.grains, 1.0);
  std::fill(diameters.begin() + jet.grains / 2, diameters.end(), jet.small_diameter);
  rng.shuffle(diameters);
  return diameters;
}

template <int D>
Particles<D> build_jet(const Scene& scene, GrainShare share) {
  Random rng(scene.run.seed);
  const double front = kTargetSurface + scene.jet.gap + 0.5;
  std::vector<Vec<D>> sites;
  std::vector<Vec<D>> wall;
  if constexpr (D == 3) {
    sites = jet_sites_3d(scene.jet, front, rng, share);
    wall = wall_sites_3d(scene.wall);
  } else {
    sites = jet_sites_2d(scene.jet, front, rng, share);
    wall = wall_sites_2d(scene.wall);
  }
  jitter_wall_sites<D>(wall, scene.wall, scene.run.seed);
  const std::vector<double> diameters = jet_diameters(scene.jet, rng);
  Vec<D> velocity = Vec<D>::Zero();
  velocity[kJetAxis<D>] = -scene.jet.speed;
  Particles<D> p;
  const auto first = static_cast<GrainId>(scene.jet.grains * share.part / share.parts);
  const bool touching = scene.jet.spacing == 1.0;
  Vec<D> front_centre = Vec<D>::Zero();
  front_centre[kJetAxis<D>] = front;
  for (std::size_t k = 0; k < sites.size(); ++k) {
    const GrainId id = first + static_cast<GrainId>(k);
    const double diameter = diameters.empty() ? 1.0 : diameters[static_cast<std::size_t>(id)];
    Vec<D> x = sites[k];
    if (touching) x = front_centre + (1.0 + kLatticeClearance) * (x - front_centre);
    // The front row sits `gap` from the target whatever the grain size: shift small grains.
    x[kJetAxis<D>] -= 0.5 * (1.0 - diameter);
    p.add(id, GrainKind::kFree, x, velocity, 0.5 * diameter,
          grain_mass<D>(scene, GrainKind::kFree, diameter));
  }
  const double wall_mass = grain_mass<D>(scene, GrainKind::kWall, kTargetGrainDiameter);
  if (scene.wall.kind == WallKind::kPlate) return p;  // the plate replaces the target grains
  auto id = static_cast<GrainId>(scene.jet.grains);
  for (const Vec<D>& x : wall)
    p.add(id++, GrainKind::kWall, x, Vec<D>::Zero(), 0.5 * kTargetGrainDiameter, wall_mass);
  return p;
}

// The share's grains of a state built whole (the binary scene's two, a gas).
template <int D>
Particles<D> share_of(Particles<D> whole, GrainShare share) {
  if (share.parts == 1) return whole;
  std::vector<std::uint32_t> keep;
  const auto n = static_cast<std::int64_t>(whole.size());
  for (std::int64_t i = 0; i < n; ++i)
    if (share.holds(i, n)) keep.push_back(static_cast<std::uint32_t>(i));
  whole.gather(keep);
  return whole;
}

// Grain 1 approaches grain 2 (at rest at the origin) along +x with the given impact parameter.
template <int D>
Particles<D> build_binary(const Scene& scene) {
  const BinarySpec& b = scene.binary;
  Vec<D> x1 = Vec<D>::Zero();
  const double lateral = b.impact_parameter;
  x1[0] = -std::sqrt(std::max(0.0, 1.0 - lateral * lateral)) - b.gap;
  x1[1] = lateral;
  Vec<D> v1 = Vec<D>::Zero();
  v1[0] = b.speed;
  Particles<D> p;
  p.add(0, GrainKind::kFree, x1, v1, 0.5, 1.0);
  p.add(1, GrainKind::kFree, Vec<D>::Zero(), Vec<D>::Zero(), 0.5, 1.0);
  if constexpr (D == 2) {
    p.spin()[0] = b.spin;
  } else {
    p.spin()[0] = Vec<3>(0.0, 0.0, b.spin);
  }
  return p;
}

// Lattice sites of one unit cell, in units of the cell edges: fcc's four, or the two of the
// rectangular cell (s, s sqrt 3) of a triangular lattice of spacing s.
template <int D>
std::vector<Vec<D>> unit_cell_basis() {
  if constexpr (D == 3)
    return {Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.5, 0.5, 0.0), Vec<3>(0.5, 0.0, 0.5),
            Vec<3>(0.0, 0.5, 0.5)};
  else
    return {Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5)};
}

// Standard normal deviate by Box-Muller, from Random's portable uniforms.
double gaussian(Random& rng) {
  const double u1 = 1.0 - rng.uniform();  // (0, 1]: the logarithm stays finite
  const double u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// gas.grains unit grains on randomly chosen lattice sites (kept in lattice order, which keeps
// neighbours close in memory), Maxwellian velocities shifted to zero momentum and scaled to
// exactly gas.temperature.
template <int D>
Particles<D> build_gas(const Scene& scene) {
  const GasSpec& gas = scene.gas;
  const GasLattice<D> lattice = gas_lattice<D>(gas);
  const std::vector<Vec<D>> basis = unit_cell_basis<D>();
  std::vector<Vec<D>> sites;
  std::array<int, D> c{};
  for (bool more = true; more;) {
    for (const Vec<D>& b : basis) {
      Vec<D> x;
      for (int d = 0; d < D; ++d) x[d] = (c[d] + b[d]) * lattice.cell_edge[d];
      sites.push_back(x);
    }
    more = false;  // odometer over the unit cells
    for (int d = 0; d < D && !more; ++d) {
      more = ++c[d] < lattice.cells[d];
      if (!more) c[d] = 0;
    }
  }
  Random rng(scene.run.seed);
  std::vector<std::uint32_t> chosen(sites.size());
  for (std::uint32_t k = 0; k < chosen.size(); ++k) chosen[k] = k;
  rng.shuffle(chosen);
  chosen.resize(gas.grains);
  std::sort(chosen.begin(), chosen.end());

  std::vector<Vec<D>> velocity(gas.grains);
  Vec<D> mean = Vec<D>::Zero();
  for (Vec<D>& v : velocity) {
    for (int d = 0; d < D; ++d) v[d] = gaussian(rng);
    mean += v;
  }
  mean /= static_cast<double>(gas.grains);
  double sum_v2 = 0.0;
  for (Vec<D>& v : velocity) {
    v -= mean;
    sum_v2 += v.squaredNorm();
  }
  const double scale = std::sqrt(gas.temperature * D * gas.grains / sum_v2);
  Particles<D> p;
  for (std::int64_t k = 0; k < gas.grains; ++k)
    p.add(k, GrainKind::kFree, sites[chosen[k]], scale * velocity[k], 0.5, 1.0);
  return p;
}

}  // namespace

// The box volume is N v / phi (v the volume of a unit grain); the lattice takes the fewest unit
// cells with at least N sites, kept close to a cube (square) in 3D (2D).
template <int D>
GasLattice<D> gas_lattice(const GasSpec& gas) {
  const double volume = gas.grains * Dim<D>::volume(0.5) / gas.phi;
  const auto sites_per_cell = static_cast<std::int64_t>(unit_cell_basis<D>().size());
  GasLattice<D> lattice;
  if constexpr (D == 3) {
    int n = 1;
    while (sites_per_cell * n * n * n < gas.grains) ++n;
    lattice.cells = {n, n, n};
    lattice.cell_edge = Vec<3>::Constant(std::cbrt(volume) / n);
    lattice.nearest = lattice.cell_edge[0] / std::sqrt(2.0);
  } else {
    // Cells (s, s sqrt 3): n_y = n_x / sqrt 3 cells make the box about square.
    const double ratio = std::sqrt(3.0);
    int nx = static_cast<int>(std::ceil(std::sqrt(gas.grains * ratio / sites_per_cell)));
    int ny = std::max(1, static_cast<int>(std::lround(nx / ratio)));
    while (sites_per_cell * nx * ny < gas.grains) ++ny;
    lattice.cells = {nx, ny};
    const double s = std::sqrt(volume / (nx * ny * ratio));
    lattice.cell_edge = Vec<2>(s, s * ratio);
    lattice.nearest = s;
  }
  for (int d = 0; d < D; ++d) lattice.box[d] = lattice.cells[d] * lattice.cell_edge[d];
  return lattice;
}

// A switch without default: a new SceneKind without its builder is a compiler warning (-Wswitch),
// not a jet built in its place.
template <int D>
Particles<D> build_initial_state(const Scene& scene, GrainShare share) {
  switch (scene.kind) {
    case SceneKind::kJet:
      return build_jet<D>(scene, share);
    case SceneKind::kBinary:
      return share_of(build_binary<D>(scene), share);
    case SceneKind::kGas:
    case SceneKind::kHcs:
      return share_of(build_gas<D>(scene), share);
  }
  throw std::logic_error("build_initial_state: a scene.kind without a builder");
}

template GasLattice<2> gas_lattice<2>(const GasSpec&);
template GasLattice<3> gas_lattice<3>(const GasSpec&);

template Particles<2> build_initial_state<2>(const Scene&, GrainShare);
template Particles<3> build_initial_state<3>(const Scene&, GrainShare);

double jet_column_length(const Scene& scene) {
  const JetSpec& j = scene.jet;
  const double sites = static_cast<double>(j.grains) / j.phi_tilde;
  if (scene.dimension == 2)
    return sites * j.spacing * j.spacing * std::sqrt(3.0) / 2.0 / j.diameter;
  const double section =
      j.shape == JetShape::kRectangle ? j.area : std::numbers::pi / 4.0 * j.diameter * j.diameter;
  return sites * std::pow(j.spacing, 3) / std::numbers::sqrt2 / section;
}

double target_grains_estimate(const Scene& scene) {
  const WallSpec& w = scene.wall;
  const double across = w.diameter / w.spacing;
  if (scene.dimension == 2) return std::floor(across) + 1.0;
  const double site_area = w.lattice == WallLattice::kHexagonal ? std::sqrt(3.0) / 2.0 : 1.0;
  return std::round(std::numbers::pi / 4.0 * across * across / site_area);
}

double gas_box_edge(const Scene& scene) {
  const double grain_volume = scene.dimension == 3 ? Dim<3>::volume(0.5) : Dim<2>::volume(0.5);
  return std::pow(static_cast<double>(scene.gas.grains) * grain_volume / scene.gas.phi,
                  1.0 / scene.dimension);
}

}  // namespace granjet
