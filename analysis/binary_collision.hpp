// Measures restitution and contact time of a two-grain collision from the simulated trajectory
// (not from [3.4]-[3.5]): the contact starts and ends where the surface gap, sampled every
// step, crosses zero (linear interpolation between samples).
#pragma once

#include <cmath>

#include "core/particles.hpp"

namespace granjet::analysis {

template <int D>
class BinaryCollisionTracker {
 public:
  // Call once per step with the two-grain state at time t.
  void observe(const Particles<D>& p, double t) {
    const Vec<D> r12 = p.position()[index(p, 1)] - p.position()[index(p, 0)];
    const double dist = r12.norm();
    const double gap = dist - p.radius()[0] - p.radius()[1];
    const Vec<D> n = r12 / dist;  // from grain 0 to grain 1
    const Vec<D> v12 = p.velocity()[index(p, 0)] - p.velocity()[index(p, 1)];
    if (have_previous_) {
      if (!touched_ && previous_gap_ > 0.0 && gap <= 0.0) {
        touched_ = true;
        onset_ = crossing(t, gap);
        approach_ = previous_v12_.dot(previous_n_);
      } else if (touched_ && !parted_ && previous_gap_ <= 0.0 && gap > 0.0) {
        parted_ = true;
        end_ = crossing(t, gap);
        separation_normal_ = n;
      }
    }
    // After separation the relative velocity still settles for a step or two (the multistep
    // integrator remembers the last contact force); keep the latest.
    if (parted_) departure_ = v12.dot(separation_normal_);
    have_previous_ = true;
    previous_t_ = t;
    previous_gap_ = gap;
    previous_n_ = n;
    previous_v12_ = v12;
  }

  bool complete() const { return parted_; }
  // Both only once complete(). e = -(v12 . n) after / (v12 . n) before.
  double restitution() const { return -departure_ / approach_; }
  double contact_time() const { return end_ - onset_; }

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("have_previous", have_previous_);
    v("previous_t", previous_t_);
    v("previous_gap", previous_gap_);
    v("previous_n", previous_n_);
    v("previous_v12", previous_v12_);
    v("touched", touched_);
    v("parted", parted_);
    v("onset", onset_);
    v("end", end_);
    v("separation_normal", separation_normal_);
    v("approach", approach_);
    v("departure", departure_);
  }

 private:
  static std::size_t index(const Particles<D>& p, GrainId id) { return p.id()[0] == id ? 0 : 1; }
  double crossing(double t, double gap) const {
    return previous_t_ + (t - previous_t_) * previous_gap_ / (previous_gap_ - gap);
  }

  bool have_previous_ = false;
  double previous_t_ = 0.0;
  double previous_gap_ = 0.0;
  Vec<D> previous_n_ = Vec<D>::Zero();
  Vec<D> previous_v12_ = Vec<D>::Zero();
  bool touched_ = false;  // the gap has closed: onset_ and approach_ are set
  bool parted_ = false;   // and opened again: end_ and separation_normal_ are set
  double onset_ = 0.0;
  double end_ = 0.0;
  Vec<D> separation_normal_ = Vec<D>::Zero();
  double approach_ = 0.0;
  double departure_ = 0.0;
};

}  // namespace granjet::analysis
