// Where the jet goes after impact (model §6): the scattering angle psi0 and, in 3D, the azimuthal
// distribution of the scattered grains and its anisotropy v2. A grain counts as scattered the
// first time a snapshot finds it farther than `radius` from the jet axis (it has left the target
// region); its velocity and position at that moment are recorded once, before the run's region
// cut can remove it.
#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/particles.hpp"

namespace granjet::analysis {

// psi0 = the angle between the incident direction -e_jet and the mean direction of the
// velocities: each velocity becomes its unit vector in its own meridional half-plane,
// (|v_perp|, v . (-e_jet))/|v|, and psi0 is the polar angle of their mean (radians; 0 = straight
// on, pi/2 = along the wall, above pi/2 = back towards the source). NaN for no velocities.
template <int D>
double scattering_angle(std::span<const Vec<D>> velocities);

// The momentum-balance reading of psi0 [4.3]: grains that arrived along e_in = -e_jet at
// `incident_speed` u0 and leave with `velocities` took the impulse sum m (v - u0 e_in) from the
// target; with 1 - cos psi0 = its component along -e_in over the incident momentum sum m u0,
// cos psi0 = sum m v . e_in / (u0 sum m). For a perfect fluid (every |v| = u0, one direction)
// it is the departure angle; slower grains at the same angle give a larger psi0. NaN for no
// grains or a cosine beyond [-1, 1] (grains that left faster than they came).
template <int D>
double momentum_scattering_angle(std::span<const Vec<D>> velocities, std::span<const double> masses,
                                 double incident_speed);

// v2 = <cos 2 phi>: with dN/dphi = v0 (1 + 2 v2 cos 2phi + ...), the cos 2phi Fourier coefficient
// over the mean v0 (the convention of elliptic flow). NaN for no angles.
double anisotropy_v2(std::span<const double> azimuths);

template <int D>
class ScatteringMeasurement {
 public:
  // `reference_azimuth`: the direction (angle from e_x about the jet axis) from the axis towards
  // the middle of the jet cross section's short side, from which phi is measured (3D).
  // `incident_speed`: u0, the speed every jet grain arrives with (the momentum reading).
  ScatteringMeasurement(double radius, double reference_azimuth, double incident_speed = 1.0)
      : radius_(radius), reference_(reference_azimuth), incident_speed_(incident_speed) {}

  // `time`: the snapshot's time, kept with each grain first seen in it.
  void observe(const Particles<D>& particles, double time);

  std::size_t count() const { return velocity_.size(); }
  std::span<const Vec<D>> velocities() const { return velocity_; }
  std::span<const double> azimuths() const { return azimuth_; }  // 3D; empty in 2D
  double psi0() const { return scattering_angle<D>(velocity_); }
  double psi0_momentum() const {
    return momentum_scattering_angle<D>(velocity_, mass_, incident_speed_);
  }
  // psi0 of the grains first seen scattered in t0 <= t <= t1: the steady flow's, without the
  // first impact's splash (the exact benchmark of model §7b is a steady solution).
  double psi0_between(double t0, double t1) const;
  double psi0_momentum_between(double t0, double t1) const;
  double v2() const { return anisotropy_v2(azimuth_); }
  // dN/dphi over `bins` equal intervals of [0, 2 pi), divided by its mean (v0).
  std::vector<double> azimuthal_distribution(int bins) const;

  template <class Visitor>
  void visit_state(Visitor& v) {
    v("seen", seen_);
    v("velocity", velocity_);
    v("time", time_);
    v("azimuth", azimuth_);
    // Checkpoints written before the momentum reading have no masses: it is NaN after such a
    // resume rather than a guess.
    if constexpr (requires { v.contains(std::string()); }) {
      if (!v.contains("mass")) {
        mass_.assign(velocity_.size(), std::numeric_limits<double>::quiet_NaN());
        return;
      }
    }
    v("mass", mass_);
  }

 private:
  double radius_;
  // The scattered grains first seen in a time window.
  struct Record {
    std::vector<Vec<D>> velocity;
    std::vector<double> mass;
  };
  Record seen_between(double t0, double t1) const;

  double reference_;
  double incident_speed_;
  std::vector<bool> seen_;  // by grain id
  std::vector<Vec<D>> velocity_;
  std::vector<double> mass_;
  std::vector<double> time_;
  std::vector<double> azimuth_;
};

extern template class ScatteringMeasurement<2>;
extern template class ScatteringMeasurement<3>;

}  // namespace granjet::analysis
