#include "analysis/gas_observer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/kinetic_theory.hpp"

namespace granjet::analysis {

template <int D>
GasObserver<D>::GasObserver(const Scene& scene, Simulator<D>& sim)
    : kind_(scene.kind),
      phi_(scene.gas.phi),
      restitution_(scene.contact.restitution),
      initial_temperature_(scene.gas.temperature),
      half_step_(0.5 * scene.dt()),
      start_(scene.gas.equilibration),
      // The observer asks for times at least half a step ahead (next_time), so a sample is
      // due at its time exactly.
      sampling_{scene.gas.equilibration, scene.gas.sample_interval, 0.0},
      grains_(static_cast<double>(sim.particles().size())) {
  observe(sim);
}

template <int D>
double GasObserver<D>::next_time(const Simulator<D>& sim) const {
  return std::max(sampling_.next, sim.time() + half_step_);
}

template <int D>
void GasObserver<D>::observe(Simulator<D>& sim) {
  const double t = sim.time();
  if (!started_) {
    if (t < start_) return;
    started_ = true;
    started_at_ = t;
    sim.record_transfers(true);
  }
  transfers_.clear();
  sim.collect_transfers(transfers_);
  for (const PairImpulse<D>& j : transfers_)
    virial_ += (j.position_i - j.position_j).dot(j.impulse);
  last_time_ = t;
  if (!sampling_.due(t)) return;
  const double temperature = 2.0 * sim.energy().kinetic / (D * grains_);
  ++samples_;
  sum_t_ += temperature;
  per_collision_.add(2.0 * static_cast<double>(sim.stats().collisions) / grains_,
                     std::log(temperature));
  in_time_.add(t, 1.0 / std::sqrt(temperature));
  sampling_.pass(t);
}

template <int D>
void GasObserver<D>::summarize(Simulator<D>& sim, nlohmann::json& summary) {
  if (samples_ <= 1) return;
  summary["measured"] = {{"temperature", temperature()}};
  if (kind_ == SceneKind::kGas) {
    summary["measured"]["compressibility"] = compressibility();
    summary["theory"] = {
        {"compressibility", D == 3 ? kinetic::carnahan_starling(phi_) : kinetic::henderson(phi_)}};
    return;
  }
  // Backend-neutral: -d ln T/dt at gas.temperature (the soft backend counts contacts, not
  // collisions).
  summary["measured"]["cooling_rate"] = cooling_rate(initial_temperature_);
  if (sim.stats().collisions > 0) {
    summary["measured"]["cooling_per_collision"] = cooling_per_collision();
    summary["theory"] = {
        {"cooling_per_collision", kinetic::cooling_per_collision(restitution_, D)}};
  }
}

template <int D>
double GasObserver<D>::temperature() const {
  return samples_ > 0 ? sum_t_ / samples_ : std::numeric_limits<double>::quiet_NaN();
}

template <int D>
double GasObserver<D>::compressibility() const {
  const double tau = last_time_ - started_at_;
  return 1.0 + virial_ / (D * grains_ * temperature() * tau);
}

template <int D>
double GasObserver<D>::cooling_per_collision() const {
  return per_collision_.slope();
}

template <int D>
double GasObserver<D>::cooling_rate(double initial_temperature) const {
  return 2.0 * std::sqrt(initial_temperature) * in_time_.slope();
}

template class GasObserver<2>;
template class GasObserver<3>;

}  // namespace granjet::analysis
