// The event-driven backend [model §8]: inelastic hard disks (2D) or spheres (3D), polydisperse,
// in free flight between binary collisions [2.1]-[2.2], with fixed (infinite-mass) wall grains
// or a flat target plate (event_driven/plate.hpp), periodic boxes for the gas scenes, and the
// soft backend's removal region for the jets.
//
// Every grain has one entry in the event calendar, its earliest event: the best collision
// found by its scans, or leaving its cell (dense periodic gases: leaving the shell of its
// neighbour list, event_driven/neighbour_shells.hpp), whichever comes first. A scan keeps the
// earliest and
// the runner-up partner, each with that partner's event counter; when the event pops and the
// counter has moved on (the partner collided meanwhile), the event is stale: the runner-up
// takes over if it is still valid, else the grain scans again (lazy invalidation, DynamO
// style). Grain states are delayed: each keeps its own time and is
// streamed only when an event touches it; particles() is a snapshot of time(), taken when first
// asked for after advance_to(t), so when (and whether) the caller looks never perturbs the
// trajectory. The time origin moves forward every few
// events per grain, so event times keep their precision in long runs.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.hpp"
#include "core/simulator.hpp"
#include "event_driven/cell_list.hpp"
#include "event_driven/collapse_detector.hpp"
#include "event_driven/contact_scan.hpp"
#include "event_driven/event_calendar.hpp"
#include "event_driven/flight.hpp"
#include "event_driven/neighbour_shells.hpp"
#include "event_driven/plate.hpp"
#include "event_driven/restitution.hpp"

namespace granjet::ed {

// kOn checks, for tests, that every collision happens at contact and that no two grains overlap
// at any advance_to(); a violation throws BlowUpError.
enum class Verification { kOff, kOn };

// How predictions find the grains in reach: kByDensity as the backend chooses (neighbour lists
// for dense 3D periodic gases, ed_simulator.cpp), kCells always by the cells with crossings
// (tests and benchmarks compare the two on the same state).
enum class NeighbourSearch { kByDensity, kCells };

template <int D>
class EdSimulator final : public Simulator<D> {
 public:
  // Wall grains must have infinite mass (GrainKind::kWall, inverse mass 0). A jet scene with
  // wall.kind = plate has the plate as its target (make_ed_simulator leaves out the target
  // grains built for the scene).
  EdSimulator(const Scene& scene, Particles<D> grains, Verification verify = Verification::kOff,
              NeighbourSearch search = NeighbourSearch::kByDensity);

  std::string_view backend() const override { return "event_driven"; }
  // Processes every event up to t. Throws BlowUpError on inelastic
  // collapse (and, verifying, on an overlap).
  void advance_to(double t) override;
  double time() const override { return time_; }
  // Taken only when asked for: a run's observers stop it every sample interval but seldom look
  // at every grain.
  const Particles<D>& particles() const override {
    if (!snapshot_current_) take_snapshot();
    return snapshot_;
  }
  // Every collision impulse since the last call, with both positions at the collision (the
  // partner's periodic image next to the grain). A plate collision has partner id kPlateId and
  // the grain's mirror image through the face as partner position (Plate::mirror).
  void collect_transfers(std::vector<PairImpulse<D>>& out) override;
  void record_transfers(bool on) override;
  SimStats stats() const override { return stats_; }
  EnergyBalance energy() const override;
  void checkpoint(StateArchive& out) override;
  void restore(const StateArchive& in) override;

 private:
  // A collision found by the grain's scans since its velocity last changed.
  struct Prediction {
    double time = kNever;
    std::uint32_t partner = 0;
    std::uint32_t partner_events = 0;  // the partner's event counter at the prediction
  };
  struct Crossing {
    double time = kNever;
    int axis = 0;
    int direction = 0;
  };

  // Bins the live grains into fresh cells and predicts every event anew, with a fresh calendar
  // and collapse watch, from the flights alone: what the constructor does, and what a
  // checkpoint does in the run that writes it and the run that resumes from it.
  void predict_anew();
  void process(std::uint32_t i);
  void collide(std::uint32_t i, std::uint32_t j);
  void hit_plate(std::uint32_t i);
  void cross_cell(std::uint32_t i);
  void renew_shell(std::uint32_t i);
  void remove(std::uint32_t i);
  bool still_valid(const Prediction& p) const {
    return p.time == kNever || events_of_[p.partner] == p.partner_events;
  }
  // Scans every grain in reach of i (and the plate) or only those of the layer i's last move
  // brought in.
  void predict_all(std::uint32_t i);
  void predict_new_layer(std::uint32_t i, const Crossing& moved);
  // Merges the collisions with the n grains grain[0..n) into i's earliest and runner-up,
  // starting from `best` and `second` (taken by value: a fresh scan's empty predictions then
  // never pass through memory); `separation` takes the grains' images (contact_scan.hpp).
  template <class Separation>
  void merge(std::uint32_t i, const std::uint32_t* grain, std::size_t n,
             const Separation& separation, Prediction best, Prediction second);
  void merge_hood(std::uint32_t i, Prediction best, Prediction second);
  void predict_exit(std::uint32_t i);
  void schedule(std::uint32_t i);
  void shift_time_origin();
  double flight_time() const;
  [[noreturn]] void report_collapse(std::uint32_t i, std::uint32_t j) const;
  void take_snapshot() const;
  void check_contact(std::uint32_t i, std::uint32_t j, double distance) const;
  void check_plate_contact(std::uint32_t i) const;
  void check_no_overlaps() const;
  bool fixed(std::uint32_t k) const { return grains_.inverse_mass()[k] == 0.0; }

  Scene scene_;
  Particles<D> grains_;    // ids, kinds, radii, masses and spins as built (never reordered)
  mutable Particles<D> snapshot_;  // the grains still in the run, at time()
  mutable bool snapshot_current_ = false;
  mutable std::int64_t snapshot_removed_ = -1;  // grains removed when its store was built
  Verification verify_;
  Restitution restitution_;
  std::optional<Plate<D>> plate_;
  std::uint32_t plate_partner_;  // the plate's index as a prediction partner: one past the grains
  // The cells of the grains (crossings); with lists (shells_), the periodic box alone.
  CellList<D> cells_;
  std::optional<NeighbourShells<D>> shells_;  // dense periodic gases (listed())
  typename CellList<D>::Neighbourhood hood_;  // scratch of the predictions
  Calendar calendar_;
  CollapseDetector collapse_;

  std::vector<Flight<D>> flight_;
  // The earliest collision, and the earliest with another partner: when the earliest goes
  // stale the runner-up takes over without a scan. A runner-up of time kUnknown (after such a
  // take-over) is not known.
  std::vector<Prediction> next_collision_;
  std::vector<Prediction> runner_up_;
  std::vector<Crossing> next_exit_;  // or, listed, the renewal (its time only)
  // Bumped whenever the velocity changes or removal; the plate's (last entry) never is.
  std::vector<std::uint32_t> events_of_;
  std::vector<std::uint32_t> last_partner_;  // partner of the last collision (self if none)
  std::vector<double> last_collision_;       // its time (-kNever if none)
  std::vector<std::uint8_t> alive_;

  std::vector<PairImpulse<D>> transfers_;
  bool recording_ = false;

  double origin_ = 0.0;           // absolute time of the internal clock's zero
  double clock_ = 0.0;            // time of the event being processed, from origin_
  double time_ = 0.0;             // absolute time of the snapshot
  std::int64_t shift_every_ = 0;  // events between time-origin shifts
  std::int64_t events_since_shift_ = 0;
  double initial_energy_ = 0.0;
  double removed_energy_ = 0.0;
  SimStats stats_;
};

// Builds the grains of the scene as the backend runs it (event_driven/scene_support.hpp: fixed
// target grains, jet lattices spaced) and the simulator.
template <int D>
std::unique_ptr<Simulator<D>> make_ed_simulator(const Scene& scene);

extern template class EdSimulator<2>;
extern template class EdSimulator<3>;
extern template std::unique_ptr<Simulator<2>> make_ed_simulator<2>(const Scene&);
extern template std::unique_ptr<Simulator<3>> make_ed_simulator<3>(const Scene&);

}  // namespace granjet::ed
