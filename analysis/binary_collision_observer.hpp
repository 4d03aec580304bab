// The measured restitution and contact time of a binary collision scene, compared in the summary
// with the requested ones. Soft grains: from the gap crossings the tracker samples every step
// (binary_collision.hpp). Hard grains never overlap, so the tracker sees no contact: e from the
// one collision's line of centres and the relative velocities before (the start) and after (the
// end of the run), e = -(v_ij . n) after / (v_ij . n) before.
#pragma once

#include "analysis/binary_collision.hpp"
#include "analysis/run_observer.hpp"
#include "core/scene.hpp"

namespace granjet::analysis {

template <int D>
class BinaryCollisionObserver final : public VisitingObserver<D, BinaryCollisionObserver<D>> {
 public:
  // Looks at the run's start at once.
  BinaryCollisionObserver(const Scene& scene, Simulator<D>& sim);

  // Every step (the gap crossings are interpolated between samples).
  double next_time(const Simulator<D>& sim) const override { return sim.time() + step_; }
  void observe(Simulator<D>& sim) override { tracker_.observe(sim.particles(), sim.time()); }
  std::string state_group() const override { return "tracker"; }
  // "measured" and "requested", once the collision is over.
  void summarize(Simulator<D>& sim, nlohmann::json& summary) override;

  template <class Visitor>
  void visit_state(Visitor& v) {
    tracker_.visit_state(v);
  }

 private:
  double step_;
  double restitution_;
  double contact_time_;
  Particles<D> initial_;
  BinaryCollisionTracker<D> tracker_;
};

extern template class BinaryCollisionObserver<2>;
extern template class BinaryCollisionObserver<3>;

}  // namespace granjet::analysis
