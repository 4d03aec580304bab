// The soft-sphere DEM backend: a force pass over a half neighbour list (contacts found, then
// evaluated, summed and integrated: soft_dem/force_pass.inl), Adams-Bashforth-2 [B.21]-[B.24]
// or velocity Verlet, the tethered or fixed target grains or the flat plate, and removal of
// grains that leave the region; run.threads shares the pass out with bit-identical results.
// Frictionless scenes compile without contact history and rotation (kFriction = false); grains
// all of one size without radius lookups (kMono); the periodic gas scenes use minimum-image
// separations (Space = PeriodicBox), all others none.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/neighbour_list.hpp"
#include "core/plate_face.hpp"
#include "core/scene.hpp"
#include "core/space.hpp"
#include "core/simulator.hpp"
#include "soft_dem/contact_law.hpp"
#include "soft_dem/contact_table.hpp"
#include "soft_dem/tethered_wall.hpp"

namespace granjet::dem {

template <int D, bool kFriction, bool kMono = false, class Space = OpenSpace<D>>
class DemSimulator final : public Simulator<D> {
 public:
  using Law = LinearSpringDashpot<D, kFriction>;

  DemSimulator(const Scene& scene, Particles<D> initial, Space space = {});

  std::string_view backend() const override { return "soft_dem"; }
  // Steps until time() >= t: the state moves on whole steps of dt.
  void advance_to(double t) override;
  double time() const override { return static_cast<double>(step_) * dt_; }
  const Particles<D>& particles() const override { return p_; }
  void collect_transfers(std::vector<PairImpulse<D>>& out) override;
  SimStats stats() const override { return stats_; }
  bool has_contact_forces() const override { return true; }
  void sample_forces(ForceSample<D>& out) const override;
  EnergyBalance energy() const override;
  void checkpoint(StateArchive& out) override;
  void restore(const StateArchive& in) override;

  double dt() const { return dt_; }
  const ContactCoefficients& coefficients() const { return law_.c; }

 private:
  void step();
  void add_travel(double largest_speed2);
  // Adams-Bashforth-2 for one grain, over raw pointers taken once per pass (see ContactSums
  // for why raw). Both return a bound on the grain's squared speed during the step.
  struct Ab2Step {
    Vec<D>* x;
    Vec<D>* v;
    Spin<D>* w;
    const Vec<D>* f;         // F(t)
    const Vec<D>* f_before;  // F(t - dt)
    Vec<D>* f_next;          // zeroed for the next pass (see force_pass)
    const Spin<D>* t;
    const Spin<D>* t_before;
    Spin<D>* t_next;
    const double* inv_m;
    const double* inv_inertia;
    double half_dt;
    // A grain with a force or torque at this step or the last.
    double advance(std::size_t i) const;
    // One without: it flies straight on and its zero forces are not touched (most of a jet in
    // flight).
    double coast(std::size_t i) const;
  };
  Ab2Step ab2_step();
  // Returns a bound on grain i's squared speed during the step.
  double predict_verlet(std::size_t i);
  void correct_verlet(std::size_t i);
  // Evaluates all forces at the current state, then calls after_row(i, forced) for every grain
  // with its total force (see force_pass.inl and Ab2Step); returns the largest value
  // after_row returned.
  template <class AfterRow>
  double force_pass(AfterRow&& after_row);
  // The listed pairs in contact, in list order, each with its history carried over.
  void find_contacts();
  // Each contact's force and torques; returns the first with an overlap beyond the limit, or
  // the number of contacts if none.
  std::size_t evaluate_contacts();
  // Geometry and relative velocity of contacts [begin, end) into contacts_; whether any
  // overlaps beyond the limit.
  bool gather_contacts(std::int64_t begin, std::int64_t end);
  // Adds contact c's force and torques to its two grains and flags them (see Ab2Step).
  // Raw pointers: Eigen stores through may-alias vector types, after which a pointer read
  // from a member would have to be read again.
  struct ContactSums {
    const std::int64_t* grain_i;
    const std::int64_t* grain_j;
    ColumnsView<D> contact_force;
    ColumnsView<ContactTable<D, kFriction>::kSpinWidth> contact_torque_i, contact_torque_j;
    Vec<D>* force;
    Spin<D>* torque;
    std::uint8_t* forced;
    void add(std::size_t c) const;
  };
  ContactSums contact_sums();
  // The tangential history of the touching pairs, by grain ids (indices change in rebuilds).
  struct History {
    GrainId a, b;
    Vec<D> shear;
  };
  std::vector<History> histories() const;
  void rebuild() { rebuild(histories()); }
  void rebuild(const std::vector<History>& history);
  void remove_escaped();
  [[noreturn]] void throw_overlap(std::size_t i, std::size_t j) const;
  void check_finite() const;
  void check_energy() const;
  std::size_t index_of(GrainId id) const { return index_of_id_[id]; }
  // Grain i's radius; one constant when all grains have the size of the first.
  double radius_of(std::span<const double> radius, std::size_t i) const {
    if constexpr (kMono) return radius[0];
    return radius[i];
  }
  // The tangential history of listed pair k: zero unless it touched at the last evaluation.
  Vec<D> history(std::uint32_t k) const {
    if constexpr (kFriction) {
      const auto c = std::lower_bound(contact_pair_.begin(), contact_pair_.end(), k);
      if (c != contact_pair_.end() && *c == k)
        return contact_shear_.template get<Vec<D>>(c - contact_pair_.begin());
    }
    return Vec<D>::Zero();
  }
  Vec<D> plate_history(std::size_t i) const {
    if constexpr (kFriction) return plate_shear_[i];
    return Vec<D>::Zero();
  }
  // Grain i against the plate (wall.kind = plate): on_contact(geometry, v_rel) while it
  // touches, on_apart() otherwise.
  template <class OnContact, class OnApart>
  void plate_contact_of(std::size_t i, OnContact&& on_contact, OnApart&& on_apart) const;
  // Adds grain i's plate force and torque (and advances its history); kTooDeep if it overlaps
  // more than run.max_overlap allows.
  // Not inlined: it must not crowd the hot grain loop of scenes without a plate.
  enum class PlateTouch : std::uint8_t { kApart, kTouching, kTooDeep };
  [[gnu::noinline]] PlateTouch add_plate_force(std::size_t i, Vec<D>& force_i, Spin<D>& torque_i);
  // Calls on_contact(i, j, k, geometry, v_rel) for listed pairs in contact, on_apart(k) for the
  // others (k indexes the pair list).
  template <class OnContact, class OnApart>
  void for_each_contact(OnContact&& on_contact, OnApart&& on_apart) const;
  // The same for the pairs of row i of the half list: on_contact(j, k, geometry, v_rel).
  template <class OnContact, class OnApart>
  void for_each_contact_of(std::size_t i, OnContact&& on_contact, OnApart&& on_apart) const;
  // The velocity of i's surface relative to j's at their contact point.
  Vec<D> relative_velocity(std::size_t i, std::size_t j, const ContactGeometry<D>& g) const;

  Scene scene_;
  Space space_;
  Particles<D> p_;
  Law law_;
  double dt_;
  double overlap_limit_;
  bool tethered_;
  TetheredWall<D> wall_;

  std::vector<Vec<D>> force_, force_prev_;  // F being accumulated (zero between passes), F(t-dt)
  std::vector<Spin<D>> torque_, torque_prev_;
  std::vector<double> inv_inertia_;
  // Per grain, bit 0: it had a force at this pass, bit 1: at the last one (see Ab2Step).
  std::vector<std::uint8_t> forced_;
  // The grains force_pass integrates with their forces, and those it lets coast.
  std::vector<std::uint32_t> forced_grains_, coasting_grains_;
  static constexpr std::uint32_t kRemoved = UINT32_MAX;
  std::vector<std::uint32_t> index_of_id_;  // kRemoved once a grain has left the region

  CellGrid<D> grid_;
  PairList pairs_;
  // The plate, its contact law (a grain against an immovable face: twice the pair's stiffness
  // and damping give the pair's e and t_c for the study's equal masses) and each grain's u_t
  // against it (frictional scenes only).
  std::optional<PlateFace<D>> plate_;
  Law plate_law_;
  std::vector<Vec<D>> plate_shear_;
  std::vector<std::uint32_t> pair_row_;  // the row i of each listed pair

  // The listed pairs in contact at the last force evaluation, by increasing list index, with
  // their u_t (frictional scenes only), and the geometry, force and torques of that evaluation.
  std::vector<std::uint32_t> contact_pair_;
  Columns<D> contact_shear_;
  ContactTable<D, kFriction> contacts_;
  std::vector<std::int64_t> contact_i_, contact_j_;  // the grains, 64-bit: vectorised gathers
  // find_contacts' scratch: each thread's stretch of the list, and the history carried over.
  std::vector<std::vector<std::uint32_t>> found_;
  std::vector<std::uint32_t> found_pair_;
  Columns<D> found_shear_;
  int threads_ = 1;

  std::int64_t step_ = 0;
  std::int64_t free_grains_ = 0;
  double travel_ = 0.0;  // bound on any grain's displacement since the last rebuild
  bool needs_rebuild_ = false;
  bool first_step_ = true;
  double removed_energy_ = 0.0;
  double initial_energy_ = 0.0;
  double last_collect_time_ = 0.0;
  SimStats stats_;
};

// The factory's single point where run-time scene choices become template instantiations.
template <int D>
std::unique_ptr<Simulator<D>> make_dem_simulator(const Scene& scene);

extern template std::unique_ptr<Simulator<2>> make_dem_simulator<2>(const Scene&);
extern template std::unique_ptr<Simulator<3>> make_dem_simulator<3>(const Scene&);

}  // namespace granjet::dem
