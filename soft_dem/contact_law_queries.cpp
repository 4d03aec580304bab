// What the factory's law registry says about a scene's contact.model, without instantiating a
// simulator (declared in dem_simulator.hpp).
#include <string>

#include "soft_dem/contact_laws.hpp"
#include "soft_dem/dem_simulator.hpp"

namespace granjet::dem {

std::string contact_law_refusal(const Scene& scene) {
  return with_contact_law(
      scene.contact.model, [&]<template <int, bool> class LawOf>(ContactLaw<LawOf>) {
        return std::string(scene.dimension == 2 ? LawOf<2, false>::kUnsupported
                                                : LawOf<3, false>::kUnsupported);
      });
}

double peak_overlap(const Scene& scene, double speed) {
  return with_contact_law(scene.contact.model,
                          [&]<template <int, bool> class LawOf>(ContactLaw<LawOf>) {
                            return LawOf<3, false>::peak_overlap(scene.contact, speed);
                          });
}

}  // namespace granjet::dem
