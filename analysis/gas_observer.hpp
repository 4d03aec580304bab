// The measured quantities of the periodic gas scenes, from what every backend hands the analysis
// (momentum transfers, energies, collision counts), over the window from gas.equilibration to
// the end of the run:
// - gas: compressibility Z = P/(n T) from the collisional virial,
//   P V = N T + (1/(D tau)) sum over collisions of r_ij . J_ij (r_ij = r_i - r_j, J_ij the
//   impulse on i), so Z = 1 + sum r_ij . J_ij / (D N T tau) [model §6, stress]; the theory it is
//   compared with is Carnahan-Starling's for hard spheres and Henderson's for hard disks;
// - hcs: cooling per collision, the least-squares slope of ln T against collisions per grain
//   (2 collisions / N: each collision counts for both grains), T = sum m v^2 / (D N), compared
//   with hard spheres' (kinetic_theory.hpp); and, for backends that do not count collisions
//   too, the cooling rate in time: Haff's law T(t) = T0 / (1 + t/t0)^2 makes T^(-1/2) linear
//   in t, and the rate -d ln T/dt at T0 is 2 sqrt(T0) times its least-squares slope.
#pragma once

#include <cstdint>
#include <vector>

#include "analysis/line_fit.hpp"
#include "analysis/run_observer.hpp"
#include "core/interval_schedule.hpp"
#include "core/scene.hpp"
#include "core/simulator.hpp"

namespace granjet::analysis {

template <int D>
class GasObserver final : public VisitingObserver<D, GasObserver<D>> {
 public:
  // Looks at the run's start at once.
  GasObserver(const Scene& scene, Simulator<D>& sim);

  double next_time(const Simulator<D>& sim) const override;
  void observe(Simulator<D>& sim) override;
  std::string state_group() const override { return "gas"; }
  // "measured" (with at least two samples) and "theory".
  void summarize(Simulator<D>& sim, nlohmann::json& summary) override;

  double temperature() const;  // mean over the window's samples
  double compressibility() const;
  double cooling_per_collision() const;
  double cooling_rate(double initial_temperature) const;
  std::int64_t samples() const { return samples_; }

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("next", sampling_.next);
    v("started", started_);
    v("started_at", started_at_);
    v("last_time", last_time_);
    v("virial", virial_);
    v("samples", samples_);
    v("sum_t", sum_t_);
    auto per_collision = v.nested("per_collision");
    per_collision_.visit_state(per_collision);
    auto in_time = v.nested("in_time");
    in_time_.visit_state(in_time);
  }

 private:
  SceneKind kind_;
  double phi_;
  double restitution_;
  double initial_temperature_;
  double half_step_;  // the least the run advances between two looks
  double start_;
  IntervalSchedule sampling_;
  bool started_ = false;
  double started_at_ = 0.0;
  double last_time_ = 0.0;
  double grains_;
  std::vector<PairImpulse<D>> transfers_;
  double virial_ = 0.0;  // sum of r_ij . J_ij over the window
  // Sums for the temperature mean and the fits of ln T against collisions per grain and of
  // T^(-1/2) against time.
  std::int64_t samples_ = 0;
  double sum_t_ = 0.0;
  LineFit per_collision_, in_time_;
};

extern template class GasObserver<2>;
extern template class GasObserver<3>;

}  // namespace granjet::analysis
