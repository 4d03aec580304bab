// Field names (a, b run over the local axes "r", "t", "z" in 3D, "x", "y" in 2D):
//   n, phi, v.a, T_g, T_alpha.a                       number density, packing fraction, mean
//                                                     velocity, temperatures (model §6)
//   stress.ab, stress_kinetic.ab, stress_contact.ab   total and parts, local frame [6.1]
//   stress_xyz.ab (3D)                                total, Cartesian components (every
//                                                     transfer, whatever wall_contacts says)
//   P, P_over_nT, P_over_nT_alpha.a                   tr(sigma)/D, [5.2] and its directional form
//   D, mu_star, eta, eta_star                         shear rate, -sigma_shear/P, -sigma_shear/D,
//                                                     eta over the dilute viscosity
//   I, sigma_Y (3D); I_s, I_T (2D)                    inertial numbers, extrapolated yield stress
//   flatness.a                                        <c^4>/<c^2>^2 of the bin's scaled velocities
// The contact stress split by contact type and direction, and the contacts' geometry,
// all from the same transfers and segment fractions A as stress_contact, in the local frame:
//   stress_contact_wall.ab     the transfers with a target (wall) grain or the plate (partner
//                              kPlateId) on either side; the flowing grains' own part is
//                              stress_contact - stress_contact_wall, and stress_contact (with
//                              stress, P, mu_star ...) is that part alone when
//                              FieldOptions::wall_contacts is false (analysis.stress_wall_contacts)
//   stress_contact_normal.ab   the part from the normal component J_n = (J.n) n of each
//                              impulse, n = (r_i - r_j)/|r_i - r_j| along the line of centres
//                              (plate: grain and mirror image); J_n r^T = (J.r) n n^T is
//                              symmetric. The tangential part is stress_contact minus this
//   contact_density            sum A / (samples V), samples those that cover time (not the
//                              window's first): soft DEM, the contacts present at the sample
//                              instants per unit volume; event-driven, the collisions between
//                              consecutive samples per unit volume (divide by
//                              analysis.sample_interval for a collision rate). Not comparable
//                              across backends
//   fabric.ab                  sum A n n^T / sum A, the fabric tensor of the contact normals
//                              (trace 1); NaN for a bin without transfers
// Like stress_contact, all of them are NaN when no transfer time was booked (stored frames).
#include "analysis/field_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "analysis/kinetic_theory.hpp"
#include "analysis/segment_clip.hpp"
#include "core/rank_team.hpp"

namespace granjet::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <class Axes, class Matrix>
void set_tensor(Table& t, const std::string& name, std::size_t row, const Axes& axes,
                const Matrix& m) {
  for (std::size_t a = 0; a < axes.size(); ++a)
    for (std::size_t b = 0; b < axes.size(); ++b)
      t.set(name + "." + std::string(axes[a]) + std::string(axes[b]), row, m(a, b));
}

}  // namespace

template <int D>
FieldAccumulator<D>::FieldAccumulator(const BinSpec& spec)
    : spec_(spec),
      coords_(spec),
      bins_(coords_.grid().size()),
      half_cells_(coords_.grid().half_cells()),
      vdf_(coords_.grid().size()) {}

template <int D>
void FieldAccumulator<D>::sample(const Particles<D>& particles,
                                 std::span<const PairImpulse<D>> transfers, double elapsed) {
  const BinGrid& grid = coords_.grid();
  const auto x = particles.position();
  const auto v = particles.velocity();
  const auto id = particles.id();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kind()[i] == GrainKind::kWall) {
      const auto k = static_cast<std::size_t>(std::max<GrainId>(id[i], 0));
      if (k >= wall_.size()) wall_.resize(k + 1, 0);  // grows to the largest wall id, once
      wall_[k] = 1;
      continue;
    }
    const double m = particles.mass()[i];
    coords_.for_each_share(x[i], particles.radius()[i],
                           [&](int bin, double volume) { bins_[bin].volume.add(volume); });
    const double lateral = coords_.lateral(x[i]), h = coords_.height(x[i]);
    const int cell = grid.half_cell_at(lateral, h);
    if (cell < 0) continue;  // the half-cell mesh covers every bin
    const Vec<D> local = coords_.frame(x[i]) * v[i];
    HalfCellExactSums& c = half_cells_[cell];
    c.mass.add(m);
    c.momentum.add(m * local);
    c.lateral.add(m * lateral);
    c.height.add(m * h);
    const int bin = grid.bin_at(lateral, h);
    if (bin < 0) continue;
    BinSums& s = bins_[bin];
    s.count.add(1.0);
    s.mass.add(m);
    s.momentum.add(m * local);
    s.second.add(m * local * local.transpose());
    s.momentum_xyz.add(m * v[i]);
    s.second_xyz.add(m * v[i] * v[i].transpose());
    vdf_.add(bin, local);
  }
  if (elapsed > 0.0) sample_transfers(transfers);
  ++samples_;
  if (elapsed > 0.0) ++transfer_samples_;
  transfer_time_ += elapsed;
}

template <int D>
void FieldAccumulator<D>::sample_transfers(std::span<const PairImpulse<D>> transfers) {
  // [C.31]-[C.33]: each transfer's J r^T, r = r_i - r_j, shared by the length fraction A of the
  // segment r_i -> r_j in each bin, rotated to the local frame at the middle of that stretch.
  // Its normal part (J.n) n r^T = (J.r) n n^T and the fabric share A n n^T go the same way.
  for (const PairImpulse<D>& t : transfers) {
    const Vec<D> r = t.position_i - t.position_j;
    const Mat w = t.impulse * r.transpose();
    const double r2 = r.squaredNorm();
    const Mat nn = r2 > 0.0 ? Mat(r * r.transpose() / r2) : Mat::Zero();
    const double j_r = t.impulse.dot(r);
    const bool wall = is_wall(t.i) || is_wall(t.j);
    clip_segment(coords_, t.position_i, t.position_j, scratch_, [&](int bin, double s0, double s1) {
      const Vec<D> mid = t.position_i + 0.5 * (s0 + s1) * (t.position_j - t.position_i);
      const auto frame = coords_.frame(mid);
      BinSums& b = bins_[bin];
      // The wall part is the same term as the total's, so a bin of wall transfers only matches
      // it exactly.
      const Mat contact = (s1 - s0) * frame * w * frame.transpose();
      b.contact.add(contact);
      b.contact_xyz.add((s1 - s0) * w);
      if (wall) b.contact_wall.add(contact);
      const Mat fabric = (s1 - s0) * frame * nn * frame.transpose();
      b.fabric.add(fabric);
      b.contact_normal.add(j_r * fabric);
      b.segments.add(s1 - s0);
    });
  }
}

template <int D>
void FieldAccumulator<D>::join(const RankTeam& team) {
  if (team.alone()) return;
  std::vector<std::int64_t> words;
  const auto each_sum = [&](auto&& visit) {
    const auto sums = [&](const char*, auto& s) { visit(s); };
    for (BinSums& b : bins_) each_bin_term(sums, b);
    for (HalfCellExactSums& c : half_cells_) each_half_cell_term(sums, c);
  };
  each_sum([&](auto& sums) { sums.append_words(words); });
  team.sum(words);
  if (team.rank() == 0) {
    std::span<const std::int64_t> rest = words;
    each_sum([&](auto& sums) { rest = sums.take_words(rest); });
  } else {
    each_sum([](auto& sums) { sums = {}; });
  }
  vdf_.join(team);
}

template <int D>
SampleRegion FieldAccumulator<D>::reach() const {
  const BinGrid& grid = coords_.grid();
  const double half = 0.5 * grid.lateral_width();  // the half-cells' overhang
  SampleRegion region;
  // |lateral| is the distance from the jet axis in either geometry (3D r, 2D |y|).
  region.within = std::max(std::abs(grid.lateral_edge(0) - half),
                           std::abs(grid.lateral_edge(grid.lateral_bins()) + half));
  region.low = spec_.height_origin;
  region.high = spec_.height_origin + grid.top();
  return region;
}

template <int D>
Table FieldAccumulator<D>::layout() const {
  const BinGrid& grid = coords_.grid();
  Table t(grid.size());
  const std::string lateral(Coordinates::kLateralName);
  for (int bin = 0; bin < grid.size(); ++bin) {
    const int k = grid.lateral_of(bin), l = grid.layer_of(bin);
    const double centre = 0.5 * (grid.lateral_edge(k) + grid.lateral_edge(k + 1));
    t.set("layer", bin, l);
    t.set("lateral_index", bin, k);
    t.set(lateral, bin, centre);
    t.set(lateral + "_over_R_tar", bin, centre / spec_.target_radius);
    t.set("h", bin, 0.5 * (grid.normal_edge(l) + grid.normal_edge(l + 1)));
    t.set("volume", bin, coords_.bin_volume(bin));
  }
  return t;
}

template <int D>
Table FieldAccumulator<D>::fields(const FieldOptions& options) const {
  const BinGrid& grid = coords_.grid();
  constexpr auto& axes = Coordinates::kAxes;
  constexpr auto shear = Coordinates::kShear;
  const double d = options.diameter;
  const auto value_of = [](const char*, const auto& sums, auto& value) { value = sums.value(); };
  std::vector<HalfCellSums<D>> half_cells(half_cells_.size());
  for (std::size_t k = 0; k < half_cells.size(); ++k)
    each_half_cell_term(value_of, half_cells_[k], half_cells[k]);
  Table t(grid.size());
  for (int bin = 0; bin < grid.size(); ++bin) {
    BinValues s;
    each_bin_term(value_of, bins_[bin], s);
    const double volume = coords_.bin_volume(bin);
    const double snapshots_volume = samples_ * volume;
    const double n = s.count / snapshots_volume;
    const double phi = s.volume / snapshots_volume;  // exact grain volume inside, not centres
    t.set("n", bin, n);
    t.set("phi", bin, phi);

    // Fluctuations about the window mean: sum m u u^T = sum m v v^T - p p^T / M. An empty bin
    // has no mean velocity and no temperature, but its kinetic stress is zero.
    const bool occupied = s.mass > 0.0;
    const Vec<D> mean = occupied ? Vec<D>(s.momentum / s.mass) : Vec<D>::Constant(kNaN);
    const Mat fluct = occupied ? Mat(s.second - s.momentum * mean.transpose()) : Mat::Zero();
    const Mat kinetic = fluct / snapshots_volume;  // [6.1], kinetic part
    const Mat kinetic_xyz =
        occupied ? Mat((s.second_xyz - s.momentum_xyz * (s.momentum_xyz / s.mass).transpose()) /
                       snapshots_volume)
                 : Mat::Zero();
    // [C.31]-[C.33]: no transfer time means no contact information (e.g. stored frames only).
    const double contact_norm = transfer_time_ > 0.0 ? 1.0 / (volume * transfer_time_) : kNaN;
    const Mat contact =
        (options.wall_contacts ? s.contact : Mat(s.contact - s.contact_wall)) * contact_norm;
    const Mat stress = kinetic + contact;
    const double t_g = fluct.trace() / (D * s.count);  // T_g = sum m u^2 / (D N)
    const double pressure = stress.trace() / D;        // P = tr(sigma)/D
    for (int a = 0; a < D; ++a) {
      const std::string axis(axes[a]);
      const double t_alpha = fluct(a, a) / s.count;  // T_alpha = sum m u_alpha^2 / N
      t.set("v." + axis, bin, mean[a]);
      t.set("T_alpha." + axis, bin, t_alpha);
      t.set("P_over_nT_alpha." + axis, bin, stress(a, a) / (n * t_alpha));  // directional [5.2]
      t.set("flatness." + axis, bin, vdf_.flatness(a, bin));
    }
    t.set("T_g", bin, t_g);
    set_tensor(t, "stress", bin, axes, stress);
    set_tensor(t, "stress_kinetic", bin, axes, kinetic);
    set_tensor(t, "stress_contact", bin, axes, contact);
    if constexpr (Coordinates::kCurvilinear)
      set_tensor(t, "stress_xyz", bin, Coordinates::kCartesianAxes,
                 Mat(kinetic_xyz + s.contact_xyz * contact_norm));
    set_tensor(t, "stress_contact_wall", bin, axes, Mat(s.contact_wall * contact_norm));
    set_tensor(t, "stress_contact_normal", bin, axes, Mat(s.contact_normal * contact_norm));
    t.set("contact_density", bin,
          transfer_time_ > 0.0 ? s.segments / (transfer_samples_ * volume) : kNaN);
    set_tensor(t, "fabric", bin, axes,
               s.segments > 0.0 ? Mat(s.fabric / s.segments) : Mat::Constant(kNaN));
    t.set("P", bin, pressure);
    t.set("P_over_nT", bin, pressure / (n * t_g));  // compare with [5.2]

    // Shear quantities along the outward lateral direction (see CartesianLayers::outward_sign).
    const double raw_rate =
        shear_rate<D>(grid, half_cells, bin, Coordinates::kLateral, Coordinates::kNormal);
    const double sign = coords_.outward_sign(bin);
    const double rate = sign * raw_rate;
    const double shear_stress = sign * stress(shear[0], shear[1]);
    const double mass = s.mass / s.count;  // the grain mass m (mean, if masses differ)
    const double eta = -shear_stress / rate;
    t.set("D", bin, raw_rate);  // D_rz (3D) or D_xy (2D) itself, not mirrored
    t.set("mu_star", bin, -shear_stress / pressure);
    t.set("eta", bin, eta);
    t.set("eta_star", bin, eta / kinetic::dilute_viscosity(t_g, mass, d, D));
    if constexpr (D == 3) {
      t.set("I", bin, rate * std::sqrt(mass / (pressure * d)));  // I = D_rz sqrt(m/(P d))
      // sigma_Y = sigma_rz + eta_kin(phi, T_g) D_rz (model §6), eta_kin from [5.4]-[5.11].
      t.set(
          "sigma_Y", bin,
          shear_stress + kinetic::kinetic_viscosity(phi, options.restitution, t_g, mass, d) * rate);
    } else {
      t.set("I_s", bin, rate * std::sqrt(mass / pressure));    // I_s = D_xy sqrt(m/P)
      t.set("I_T", bin, std::sqrt(t_g / (pressure * d * d)));  // I_T = sqrt(T_g/(P d^2))
    }
  }
  return t;
}

template class FieldAccumulator<2>;
template class FieldAccumulator<3>;

}  // namespace granjet::analysis
