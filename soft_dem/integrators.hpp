// The soft DEM's two time integrators, one grain at a time over raw arrays (the force pass calls
// them from its update loops, soft_dem/force_pass.hpp): Adams-Bashforth-2, the study's, and
// velocity Verlet. Each move returns a bound on the grain's squared speed during the step, from
// which the simulator knows when the neighbour list must be rebuilt. kRotation: whether the
// grains turn (spins integrated with the torques), as the contact law says.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/dim.hpp"
#include "soft_dem/lane_vec.hpp"

namespace granjet::dem {

// The larger of the two, where a NaN wins and stays (so a blow-up is not lost in a maximum).
inline double sticky_max(double largest, double value) {
  return value > largest || std::isnan(value) ? value : largest;
}

// a where mask has all bits set, b where it has none. In bits: GCC turns a ?: whose one side is
// the value already stored into a branch or a masked store, and then does not vectorise.
inline double select_bits(std::uint64_t mask, double a, double b) {
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & mask) |
                               (std::bit_cast<std::uint64_t>(b) & ~mask));
}

// Adams-Bashforth-2 for velocities and spins, trapezoid for positions (model §3), with
// F(t - dt) = F(t) on the first step:
//   [B.21] v(t+dt) = v(t) + dt/(2m) (3 F(t) - F(t-dt))
//   [B.22] w(t+dt) = w(t) + dt/(2I) (3 M(t) - M(t-dt))
//   [B.23] x(t+dt) = x(t) + dt/2 (v(t+dt) + v(t))
// (model §3 heads these three updates with four labels and does not number them one by one:
// the labels here follow its order, and [B.24] is matched to none). Raw pointers, taken once
// per pass: Eigen stores through may-alias vector types, after which a pointer read from a
// member would have to be read again.
template <int D, bool kRotation>
struct Ab2Step {
  Vec<D>* x;
  Vec<D>* v;
  Spin<D>* w;
  const Vec<D>* f;         // F(t)
  const Vec<D>* f_before;  // F(t - dt)
  Vec<D>* f_next;          // zeroed for the next pass (the force pass sums into it)
  const Spin<D>* t;
  const Spin<D>* t_before;
  Spin<D>* t_next;
  const double* inv_m;
  const double* inv_inertia;
  double half_dt;

  // A grain with a force or torque at this step or the last.
  double advance(std::size_t i) const {
    const Vec<D> v_new = v[i] + (half_dt * inv_m[i]) * (3.0 * f[i] - f_before[i]);  // [B.21]
    x[i] += half_dt * (v[i] + v_new);                                               // [B.23]
    // The step moved grain i by dt |v + v_new|/2 <= dt max(|v|, |v_new|).
    const double speed2 = std::max(v[i].squaredNorm(), v_new.squaredNorm());
    v[i] = v_new;
    f_next[i].setZero();  // the swap after the pass makes f F(t-dt) and this the next F
    if constexpr (kRotation) {
      w[i] += (half_dt * inv_inertia[i]) * (3.0 * t[i] - t_before[i]);  // [B.22]
      t_next[i] = Dim<D>::zero_spin();
    }
    return speed2;
  }

  // A grain another rank moves (a ghost, whose owner's state overwrites this one after the
  // pass): only its sums for the next pass start from zero. Its move counts on its owner.
  double leave(std::size_t i) const {
    f_next[i].setZero();
    if constexpr (kRotation) t_next[i] = Dim<D>::zero_spin();
    return 0.0;
  }

  // Grains [begin, end) without a force (pushed[i] == 0) fly straight on and their zero forces
  // are not touched (most of a jet in flight); the pushed ones are left to advance. Returns the
  // largest squared speed of the coasting ones. One straight loop over all the grains, which
  // GCC vectorises: whether a grain of a jet is pushed is as good as random, so a list of the
  // coasting ones would cost a compaction and indirect loads for no arithmetic saved.
  double coast(const std::uint8_t* pushed, std::int64_t begin, std::int64_t end) const {
    static_assert(sizeof(Vec<D>) == D * sizeof(double));
    double* position = reinterpret_cast<double*>(x);
    const double* velocity = reinterpret_cast<const double*>(v);
    const double step = half_dt;  // a local: the stores through position may alias a member
    // Squared speeds (never negative) compared as bits: the same order as the numbers, with
    // any NaN above them all, so a blow-up is kept (as sticky_max does) by a maximum that
    // vectorises.
    std::uint64_t largest = 0;
#pragma GCC ivdep
    for (std::int64_t i = begin; i < end; ++i) {
      const std::uint64_t moving = std::uint64_t{pushed[i] != 0} - 1;  // all bits, or none
      const LaneVec<D> x_i = LaneVec<D>::at(position, i), v_i = LaneVec<D>::at(velocity, i);
      const LaneVec<D> moved = x_i + step * (v_i + v_i);  // v_new = v: advance's rounding
      for (int d = 0; d < D; ++d) position[D * i + d] = select_bits(moving, moved[d], x_i[d]);
      largest = std::max(largest, std::bit_cast<std::uint64_t>(v_i.squaredNorm()) & moving);
    }
    return std::bit_cast<double>(largest);
  }
};

// Velocity Verlet. The predictor moves x += dt v + dt^2/(2m) F(t) and v += dt/m F(t); the
// dashpots then see this predicted v(t+dt) rather than the half-step velocity, which would lag
// by dt/2 and bias the restitution by O(dt) (LAMMPS's nve/sphere gives e = 0.7567 for 0.75 at
// dt = t_c/50). The corrector, once the forces at t + dt are known:
// v(t+dt) = v(t) + dt/(2m) (F(t) + F(t+dt)).
template <int D, bool kRotation>
struct VerletStep {
  Vec<D>* x;
  Vec<D>* v;
  Spin<D>* w;
  const Vec<D>* f;   // F(t + dt), summed by the force pass between predictor and corrector
  Vec<D>* f_before;  // F(t); the corrector zeroes it for the next pass
  const Spin<D>* t;
  Spin<D>* t_before;
  const double* inv_m;
  const double* inv_inertia;
  double dt;

  // Returns a bound on grain i's squared speed during the step.
  double predict(std::size_t i) const {
    const Vec<D> dv = (dt * inv_m[i]) * f_before[i];
    x[i] += dt * (v[i] + 0.5 * dv);
    const double speed2 = std::max(v[i].squaredNorm(), (v[i] + dv).squaredNorm());
    v[i] += dv;
    if constexpr (kRotation) w[i] += (dt * inv_inertia[i]) * t_before[i];
    return speed2;
  }

  // A grain without a force at t or t + dt has nothing to correct.
  void correct(std::size_t i) const {
    v[i] += (0.5 * dt * inv_m[i]) * (f[i] - f_before[i]);
    f_before[i].setZero();  // as Ab2Step::advance
    if constexpr (kRotation) {
      w[i] += (0.5 * dt * inv_inertia[i]) * (t[i] - t_before[i]);
      t_before[i] = Dim<D>::zero_spin();
    }
  }
};

}  // namespace granjet::dem
