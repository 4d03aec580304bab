#include "analysis/scattering.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/jet_geometry.hpp"

namespace granjet::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 2.0 * std::numbers::pi;

template <int D>
Vec<D> perpendicular(const Vec<D>& v) {
  Vec<D> p = v;
  p[kJetAxis<D>] = 0.0;
  return p;
}

}  // namespace

template <int D>
double scattering_angle(std::span<const Vec<D>> velocities) {
  double along_wall = 0.0, forward = 0.0;
  std::size_t n = 0;
  for (const Vec<D>& v : velocities) {
    const double speed = v.norm();
    if (speed == 0.0) continue;
    along_wall += perpendicular<D>(v).norm() / speed;
    forward += -v[kJetAxis<D>] / speed;  // the jet travels along -e_jet
    ++n;
  }
  return n == 0 ? kNaN : std::atan2(along_wall, forward);
}

template <int D>
double momentum_scattering_angle(std::span<const Vec<D>> velocities, std::span<const double> masses,
                                 double incident_speed) {
  double forward = 0.0, mass = 0.0;
  for (std::size_t k = 0; k < velocities.size(); ++k) {
    forward += masses[k] * -velocities[k][kJetAxis<D>];  // the jet travels along -e_jet
    mass += masses[k];
  }
  return mass > 0.0 ? std::acos(forward / (incident_speed * mass)) : kNaN;  // NaN beyond [-1, 1]
}

double anisotropy_v2(std::span<const double> azimuths) {
  if (azimuths.empty()) return kNaN;
  double sum = 0.0;
  for (double phi : azimuths) sum += std::cos(2.0 * phi);
  return sum / azimuths.size();
}

template <int D>
void ScatteringMeasurement<D>::observe(const Particles<D>& particles, double time) {
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kind()[i] == GrainKind::kWall) continue;
    const Vec<D>& x = particles.position()[i];
    if (perpendicular<D>(x).norm() <= radius_) continue;
    const auto id = static_cast<std::size_t>(particles.id()[i]);
    if (id >= seen_.size()) seen_.resize(id + 1, false);
    if (seen_[id]) continue;
    seen_[id] = true;
    velocity_.push_back(particles.velocity()[i]);
    mass_.push_back(particles.mass()[i]);
    time_.push_back(time);
    if constexpr (D == 3) azimuth_.push_back(std::atan2(x.y(), x.x()) - reference_);
  }
}

template <int D>
typename ScatteringMeasurement<D>::Record ScatteringMeasurement<D>::seen_between(double t0,
                                                                                 double t1) const {
  Record r;
  for (std::size_t k = 0; k < velocity_.size(); ++k)
    if (time_[k] >= t0 && time_[k] <= t1) {
      r.velocity.push_back(velocity_[k]);
      r.mass.push_back(mass_[k]);
    }
  return r;
}

template <int D>
double ScatteringMeasurement<D>::psi0_between(double t0, double t1) const {
  return scattering_angle<D>(seen_between(t0, t1).velocity);
}

template <int D>
double ScatteringMeasurement<D>::psi0_momentum_between(double t0, double t1) const {
  const Record r = seen_between(t0, t1);
  return momentum_scattering_angle<D>(r.velocity, r.mass, incident_speed_);
}

template <int D>
std::vector<double> ScatteringMeasurement<D>::azimuthal_distribution(int bins) const {
  std::vector<double> out(bins, 0.0);
  if (azimuth_.empty()) return out;
  for (double phi : azimuth_) {
    const double wrapped = phi - kTwoPi * std::floor(phi / kTwoPi);
    out[std::min(bins - 1, static_cast<int>(wrapped / kTwoPi * bins))] += 1.0;
  }
  for (double& c : out) c *= static_cast<double>(bins) / azimuth_.size();  // mean 1
  return out;
}

template double scattering_angle<2>(std::span<const Vec<2>>);
template double scattering_angle<3>(std::span<const Vec<3>>);
template double momentum_scattering_angle<2>(std::span<const Vec<2>>, std::span<const double>,
                                             double);
template double momentum_scattering_angle<3>(std::span<const Vec<3>>, std::span<const double>,
                                             double);
template class ScatteringMeasurement<2>;
template class ScatteringMeasurement<3>;

}  // namespace granjet::analysis
