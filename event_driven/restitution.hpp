// The restitution coefficient of one collision, by the law chosen in the scene [model §8]:
// - constant: e0 = contact.restitution;
// - velocity_dependent (Goldman et al., Bizon et al. 1998): e(v_n) = 1 - (1 - e0)(v_n/v0)^(3/4)
//   for v_n < v0, e0 above; slow collisions are nearly elastic, which prevents inelastic
//   collapse;
// - tc_model (Luding and McNamara 1998): e = 1 when either grain collided less than tc ago.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/scene.hpp"

namespace granjet::ed {

class Restitution {
 public:
  explicit Restitution(const Scene& scene)
      : law_(scene.ed.restitution_law),
        e0_(scene.contact.restitution),
        v0_(scene.ed.v0),
        tc_(scene.ed.tc) {}

  // v_n > 0: normal approach speed; since_i, since_j: time since each grain's previous
  // collision (kNever for none, and for fixed wall grains, which meet many independent grains).
  double operator()(double v_n, double since_i, double since_j) const {
    switch (law_) {
      case RestitutionLaw::kConstant:
        return e0_;
      case RestitutionLaw::kVelocityDependent:
        return v_n < v0_ ? 1.0 - (1.0 - e0_) * std::pow(v_n / v0_, 0.75) : e0_;
      case RestitutionLaw::kTcModel:
        return std::min(since_i, since_j) < tc_ ? 1.0 : e0_;
    }
    return e0_;
  }

 private:
  RestitutionLaw law_;
  double e0_;
  double v0_;
  double tc_;
};

}  // namespace granjet::ed
