// Time-averaged fields per bin (model §6): density, packing fraction, mean velocity, T_g and
// T_alpha, kinetic and contact stress [5.1]/[6.1], [C.31]-[C.33], pressure, strain rate, mu*,
// inertial numbers, viscosity and the extrapolated yield stress. One accumulation code for both
// geometries (3D rings, 2D layers); the geometry is the coordinate class chosen by D.
//
// Both backends feed it the same way: a snapshot of the grains plus the momentum transfers since
// the previous snapshot and the time they cover (soft DEM: pair force x elapsed time; ED: every
// collision impulse). The contact stress is sum(J r^T A)/(V tau) over all transfers of the
// window, tau the total time they cover; the kinetic part is the average over snapshots.
//
// Tensors are rotated to the local frame (e_r, e_theta, e_z) of each grain and each transfer
// before they are summed: a ring spans every theta, so a Cartesian ring average has no single
// rotation to cylindrical components, and mean-velocity subtraction must happen in the local
// frame (the mean radial flow of a ring averages to zero in Cartesian axes). The Cartesian sums
// are kept too. Fluctuations are taken about the window's mean velocity of the bin (momentum
// over mass summed over the window), which needs only sums and avoids the (N-1)/N bias of a
// per-snapshot mean in sparse bins. Wall grains are not part of the flow fields; their contacts
// with flowing grains do count in the contact stress, and their part of it is kept apart
// (stress_contact_wall), beside the normal part and the fabric of the transfers. Every sum is
// exact (analysis/exact_sums.hpp): the fields are the same bits in whatever order the grains and
// transfers of a snapshot come.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "analysis/bin_grid.hpp"
#include "analysis/cartesian_layers.hpp"
#include "analysis/cylindrical_rings.hpp"
#include "analysis/exact_sums.hpp"
#include "analysis/strain_rate.hpp"
#include "analysis/table.hpp"
#include "analysis/velocity_distribution.hpp"
#include "core/particles.hpp"
#include "core/sample_region.hpp"
#include "core/simulator.hpp"

namespace granjet::analysis {

template <int D>
using BinCoordinates = std::conditional_t<D == 3, CylindricalRings, CartesianLayers>;

// What the derived fields need beyond the sums.
struct FieldOptions {
  double restitution = 0.75;  // e in eta_kin of the yield stress: e-bar [2.55] for frictional
  double diameter = 1.0;      // d in I, I_T, eta* and eta_kin
  // Whether the contact stress counts the transfers with target grains or the plate; without
  // them it is the flowing grains' own (stress_contact - stress_contact_wall).
  bool wall_contacts = true;
};

template <int D>
class FieldAccumulator final : public OwnSampler<D> {
 public:
  using Coordinates = BinCoordinates<D>;
  using Mat = Eigen::Matrix<double, D, D>;

  explicit FieldAccumulator(const BinSpec& spec);

  const Coordinates& coordinates() const { return coords_; }
  // The cylinder (3D; 2D the strip) about the jet axis that a grain or transfer must reach into
  // to count in sample(): the bins and the half-cells beyond their lateral ends.
  SampleRegion reach() const;
  // Adds one snapshot and the transfers of the `elapsed` time before it. The first snapshot of a
  // window comes with elapsed = 0 (earlier transfers are outside the window): transfers that
  // cover no time count nothing.
  void sample(const Particles<D>& particles, std::span<const PairImpulse<D>> transfers,
              double elapsed) override;
  // Over MPI ranks, each rank sums its own grains and contacts (Simulator::sample_own): the
  // sums join onto rank 0, and the other ranks start again from none. Each rank keeps the
  // velocities of its grains (a checkpoint stores them in its share); the velocity
  // distributions' statistics join. The sample counts and times are alike on every rank and
  // stay as they are.
  void join(const RankTeam& team) override;
  void save_own(StateWriter& out) override { visit_own_state(out); }
  void restore_own(StateReader& in) override {
    if (in.nested("vdf").in_share("bin")) visit_own_state(in);
  }
  int samples() const { return samples_; }
  double transfer_time() const { return transfer_time_; }

  // Per bin: "layer", "lateral_index", the centre ("r" or "y", its ratio to R_tar
  // "r_over_R_tar" or "y_over_R_tar", and the height "h" above the wall) and "volume".
  Table layout() const;
  // The time-averaged fields, one row per bin; names in field_accumulator.cpp's header comment.
  Table fields(const FieldOptions& options) const;
  const VelocityDistribution<D>& velocity_distribution() const { return vdf_; }

  // Checkpoints: the sums so far (the bins themselves come from the configuration).
  template <class Visitor>
  void visit_state(Visitor& v) {
    v.each("bins", bins_, [](auto& b, BinSums& s) {
      each_bin_term([&](const char* name, auto& sums) { sums.visit(b, name); }, s);
    });
    v.each("half_cells", half_cells_, [](auto& c, HalfCellExactSums& h) {
      each_half_cell_term([&](const char* name, auto& sums) { sums.visit(c, name); }, h);
    });
    visit_own_state(v);
    v("samples", samples_);
    v("transfer_samples", transfer_samples_);
    v("transfer_time", transfer_time_);
    v("wall", wall_);
  }

 private:
  // What stays each rank's own after a join.
  template <class Visitor>
  void visit_own_state(Visitor& v) {
    auto vdf = v.share("vdf");
    vdf_.visit_state(vdf);
  }

  // Summed over the window's snapshots and transfers, exactly (analysis/exact_sums.hpp).
  template <class Scalar, class Vector, class Matrix>
  struct BinTerms {
    Scalar count{};   // grain centres, summed over snapshots
    Scalar volume{};  // grain volume (area) inside the bin
    Scalar mass{};
    Vector momentum{};  // local frame
    Matrix second{};    // sum m v v^T, local frame
    Vector momentum_xyz{};
    Matrix second_xyz{};
    Matrix contact{};  // sum J r^T A, local frame
    Matrix contact_xyz{};
    Matrix contact_wall{};    // sum J r^T A of transfers with a wall grain or plate
    Matrix contact_normal{};  // sum (J.n) n r^T A, local frame
    Matrix fabric{};          // sum A n n^T, local frame
    Scalar segments{};        // sum A
  };
  using BinSums = BinTerms<ExactSums<double>, ExactSums<Vec<D>>, ExactSums<Mat>>;
  using BinValues = BinTerms<double, Vec<D>, Mat>;  // what BinSums add up to

  struct HalfCellExactSums {  // HalfCellSums<D> (analysis/strain_rate.hpp), exactly
    ExactSums<double> mass;
    ExactSums<Vec<D>> momentum;
    ExactSums<double> lateral, height;
  };

  // The members of one or more BinTerms (or half-cells) side by side, each with its name in
  // checkpoints: visit(name, the member of each). One list for checkpoints, joins and values.
  template <class Visit, class... Terms>
  static void each_bin_term(Visit&& visit, Terms&... t) {
    visit("count", t.count...);
    visit("volume", t.volume...);
    visit("mass", t.mass...);
    visit("momentum", t.momentum...);
    visit("second", t.second...);
    visit("momentum_xyz", t.momentum_xyz...);
    visit("second_xyz", t.second_xyz...);
    visit("contact", t.contact...);
    visit("contact_xyz", t.contact_xyz...);
    visit("contact_wall", t.contact_wall...);
    visit("contact_normal", t.contact_normal...);
    visit("fabric", t.fabric...);
    visit("segments", t.segments...);
  }
  template <class Visit, class... Cells>
  static void each_half_cell_term(Visit&& visit, Cells&... c) {
    visit("mass", c.mass...);
    visit("momentum", c.momentum...);
    visit("lateral", c.lateral...);
    visit("height", c.height...);
  }

  void sample_transfers(std::span<const PairImpulse<D>> transfers);

  // Whether partner `id` is a target (wall) grain or the plate (kPlateId, the only negative id).
  bool is_wall(GrainId id) const {
    return id < 0 || (static_cast<std::size_t>(id) < wall_.size() && wall_[id] != 0);
  }

  BinSpec spec_;
  Coordinates coords_;
  std::vector<BinSums> bins_;
  std::vector<HalfCellExactSums> half_cells_;
  VelocityDistribution<D> vdf_;
  int samples_ = 0;
  int transfer_samples_ = 0;  // samples that cover time (elapsed > 0)
  double transfer_time_ = 0.0;
  std::vector<double> scratch_;
  // Indexed by grain id: 1 for wall grains seen in any snapshot so far. Ids are stable and a
  // grain's kind never changes, so entries are only ever set: a grain removed since still counts
  // as what it was, and an id never seen (beyond the end) as a flowing grain.
  std::vector<std::uint8_t> wall_;
};

extern template class FieldAccumulator<2>;
extern template class FieldAccumulator<3>;

}  // namespace granjet::analysis
