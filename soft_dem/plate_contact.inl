// Part of soft_dem/dem_simulator.cpp (included there, inside namespace granjet::dem, before the
// explicit instantiations): the grain-plate contact of wall.kind = plate.
#pragma once

// The plate is a thin disk (3D) or segment (2D), core/plate_face.hpp: a grain touches it when
// the face point nearest its centre, on the face or its rim, lies within its radius. Over the
// face the normal is the face's (either side: a grain that got behind a narrow plate meets its
// back); beside it, the rim's, so a grain coming in over the edge is pushed off smoothly instead
// of finding itself deep in the face. The lever arm is the distance to that point.
template <int D, bool kFriction, bool kMono, class Space>
template <class OnContact, class OnApart>
void DemSimulator<D, kFriction, kMono, Space>::plate_contact_of(std::size_t i,
                                                              OnContact&& on_contact,
                                                              OnApart&& on_apart) const {
  const Vec<D>& x = p_.position()[i];
  const double r = radius_of(p_.radius(), i);
  const Vec<D> from_face = x - plate_->nearest_point(x);
  const double distance = from_face.norm();
  if (distance >= r) {
    on_apart();
    return;
  }
  // A centre exactly on the face has no direction to it: push it to the front.
  const Vec<D> n = distance > 0.0 ? Vec<D>(from_face / distance) : PlateFace<D>::outward();
  const ContactGeometry<D> g{n, r - distance, distance, 0.0};
  Vec<D> v_rel = p_.velocity()[i];
  if constexpr (kFriction) v_rel -= Dim<D>::spin_cross(g.lever_i * p_.spin()[i], g.n);
  on_contact(g, v_rel);
}

template <int D, bool kFriction, bool kMono, class Space>
auto DemSimulator<D, kFriction, kMono, Space>::add_plate_force(std::size_t i, Vec<D>& force_i,
                                                               Spin<D>& torque_i) -> PlateTouch {
  PlateTouch touch = PlateTouch::kApart;
  Vec<D> no_history = Vec<D>::Zero();
  plate_contact_of(
      i,
      [&](const ContactGeometry<D>& g, const Vec<D>& v_rel) {
        const bool too_deep = g.overlap > overlap_limit_ * radius_of(p_.radius(), i);
        touch = too_deep ? PlateTouch::kTooDeep : PlateTouch::kTouching;
        Vec<D>& shear = kFriction ? plate_shear_[i] : no_history;
        const Vec<D> f = plate_law_.force(g, v_rel, shear);
        force_i += f;
        if constexpr (kFriction) torque_i -= g.lever_i * Dim<D>::cross(g.n, f);
      },
      [&] {
        if constexpr (kFriction) plate_shear_[i].setZero();
      });
  return touch;
}
