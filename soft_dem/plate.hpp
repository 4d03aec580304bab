// The flat target plate (wall.kind = plate) of the soft DEM: the face and rim of
// core/plate_face.hpp, the contact law a grain feels there, and each grain's tangential history
// against it (laws that keep one).
//
// A grain touches the plate when the face point nearest its centre, on the face or its rim,
// lies within its radius. Over the face the normal is the face's (either side: a grain that got
// behind a narrow plate meets its back); beside it, the rim's, so a grain coming in over the
// edge is pushed off smoothly instead of finding itself deep in the face. The lever arm is the
// distance to that point.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/dim.hpp"
#include "core/particles.hpp"
#include "core/plate_face.hpp"
#include "soft_dem/contact_geometry.hpp"
#include "soft_dem/rolling_resistance.hpp"

namespace granjet::dem {

// Law: the contact law of a grain against the immovable face (a law's Wall variant, whose
// geometry has lever_j = 0).
template <int D, class Law>
class Plate : public PlateFace<D> {
 public:
  enum class Touch : std::uint8_t { kApart, kTouching, kTooDeep };

  Plate(double diameter, const Law& law, std::size_t grains) : PlateFace<D>(diameter), law_(law) {
    if constexpr (Law::kNeedsHistory) shear_.assign(grains, Vec<D>::Zero());
  }

  // A grain (centre x, radius r, velocity v, spin w) against the plate: on_contact(geometry,
  // v_rel) while it touches, on_apart() otherwise.
  template <class OnContact, class OnApart>
  void contact(const Vec<D>& x, double r, const Vec<D>& v, const Spin<D>& w, OnContact&& on_contact,
               OnApart&& on_apart) const {
    const Vec<D> from_face = x - this->nearest_point(x);
    const double distance = from_face.norm();
    if (distance >= r) {
      on_apart();
      return;
    }
    // A centre exactly on the face has no direction to it: push it to the front.
    const Vec<D> n = distance > 0.0 ? Vec<D>(from_face / distance) : PlateFace<D>::outward();
    const ContactGeometry<D> g{n, r - distance, distance, 0.0};
    Vec<D> v_rel = v;
    if constexpr (Law::kNeedsRotation) v_rel -= Dim<D>::spin_cross(g.lever_i * w, g.n);
    on_contact(g, v_rel);
  }

  // Adds grain i's plate force and torque and advances its history; kTooDeep if it overlaps
  // more than overlap_limit of its radius. Not inlined: it must not crowd the hot grain loop of
  // scenes without a plate.
  [[gnu::noinline]] Touch add_force(std::size_t i, const Vec<D>& x, double r, const Vec<D>& v,
                                    const Spin<D>& w, double overlap_limit, Vec<D>& force_i,
                                    Spin<D>& torque_i) {
    Touch touch = Touch::kApart;
    Vec<D> no_history = Vec<D>::Zero();
    contact(
        x, r, v, w,
        [&](const ContactGeometry<D>& g, const Vec<D>& v_rel) {
          touch = g.overlap > overlap_limit * r ? Touch::kTooDeep : Touch::kTouching;
          Vec<D>& shear = Law::kNeedsHistory ? shear_[i] : no_history;
          const Vec<D> f = law_.force(g, v_rel, shear);
          force_i += f;
          if constexpr (Law::kNeedsRotation) torque_i -= g.lever_i * Dim<D>::cross(g.n, f);
          if constexpr (rolls<Law>) torque_i += law_.rolling_torque(g, w, f);  // the face is still
        },
        [&] {
          if constexpr (Law::kNeedsHistory) shear_[i].setZero();
        });
    return touch;
  }

  // Grain i's force at contact g without advancing its history (sampling).
  Vec<D> force(std::size_t i, const ContactGeometry<D>& g, const Vec<D>& v_rel) const {
    Vec<D> shear = shear_of(i);  // a copy
    return law_.force(g, v_rel, shear);
  }
  double elastic_energy(std::size_t i, const ContactGeometry<D>& g) const {
    return law_.elastic_energy(g, shear_of(i));
  }

  // Whether the law keeps a u_t per grain: then shear() has a row for every grain held, none
  // when a rank holds no grains.
  static constexpr bool keeps_shear() { return Law::kNeedsHistory; }
  // Each grain's u_t against the plate, in grain order (empty without history): the simulator
  // reorders it with the grains and stores it in checkpoints.
  std::vector<Vec<D>>& shear() { return shear_; }
  const std::vector<Vec<D>>& shear() const { return shear_; }
  void gather(std::span<const std::uint32_t> order) {
    if (!shear_.empty()) Particles<D>::gather_one(shear_, order);
  }
  void compact(const typename Particles<D>::Moves& moves, std::size_t kept, std::size_t room) {
    if (!shear_.empty()) Particles<D>::compact_one(shear_, moves, kept, room);
  }

 private:
  Vec<D> shear_of(std::size_t i) const {
    if constexpr (Law::kNeedsHistory) return shear_[i];
    return Vec<D>::Zero();
  }

  Law law_;
  std::vector<Vec<D>> shear_;
};

}  // namespace granjet::dem
