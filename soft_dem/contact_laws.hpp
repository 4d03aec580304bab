// The registry of soft contact laws: where a value of contact.model becomes a law type. Any
// backend that evaluates soft contacts includes it; each law is one header (the prototype,
// with the interface a law provides, is linear_spring_dashpot.hpp) and one case below. A law
// is a normal part with, when friction needs one, the tangential part of
// coulomb_tangential.hpp; optional parts either wrap it (Rolling<Law>, rolling_resistance.hpp)
// or are a term its normal force takes, zero for none (adhesion.hpp).
#pragma once

#include "core/scene.hpp"
#include "soft_dem/hertz_mindlin.hpp"
#include "soft_dem/linear_spring_dashpot.hpp"
#include "soft_dem/rolling_resistance.hpp"

namespace granjet::dem {

// A contact law, as the template Law<D, kFriction> a backend instantiates.
template <template <int, bool> class LawOf>
struct ContactLaw {};

// Calls choose(ContactLaw<...>{}) with the law of contact.model.
template <class Choose>
decltype(auto) with_contact_law(ContactModel model, Choose&& choose) {
  switch (model) {
    case ContactModel::kHertz:
      return choose(ContactLaw<HertzMindlin>{});
    case ContactModel::kLinear:
      break;
  }
  return choose(ContactLaw<LinearSpringDashpot>{});
}

}  // namespace granjet::dem
