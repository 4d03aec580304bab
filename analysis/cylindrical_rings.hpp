// 3D bin geometry (model §6): rings about the jet axis (the z axis) above the target plane.
// Lateral coordinate r = sqrt(x^2 + y^2), height h = z - height origin; the local frame is
// (e_r, e_theta, e_z) at each grain or transfer position.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string_view>
#include <utility>
#include <vector>

#include "analysis/bin_grid.hpp"
#include "analysis/grain_overlap.hpp"
#include "core/dim.hpp"

namespace granjet::analysis {

class CylindricalRings {
 public:
  static constexpr int kDim = 3;
  using VecT = Vec<3>;
  using Mat = Eigen::Matrix3d;
  // Local-frame axis names as used in field names ("stress.rz", "T_alpha.t").
  static constexpr std::array<std::string_view, 3> kAxes{"r", "t", "z"};
  static constexpr std::array<std::string_view, 3> kCartesianAxes{"x", "y", "z"};
  static constexpr std::string_view kLateralName = "r";
  static constexpr int kLateral = 0;  // local-frame index of the lateral velocity v_r
  static constexpr int kNormal = 2;   // ... and of the normal one v_z
  static constexpr std::array<int, 2> kShear{0, 2};  // sigma_rz of mu* = -sigma_rz/P (model §6)
  // A ring's Cartesian tensor differs from its cylindrical one, so both are reported.
  static constexpr bool kCurvilinear = true;

  explicit CylindricalRings(const BinSpec& spec)
      : grid_(0.0, spec.target_radius, spec.lateral_bins, spec.layer_height, spec.layers),
        origin_(spec.height_origin) {}

  const BinGrid& grid() const { return grid_; }
  double lateral(const VecT& x) const { return std::hypot(x.x(), x.y()); }
  double height(const VecT& x) const { return x.z() - origin_; }

  // Rows e_r, e_theta, e_z at x: v_local = frame v, sigma_local = frame sigma frame^T. On the
  // axis e_r is undefined; e_x is taken (a set of measure zero).
  Mat frame(const VecT& x) const {
    const double r = lateral(x);
    const double c = r > 0.0 ? x.x() / r : 1.0;
    const double s = r > 0.0 ? x.y() / r : 0.0;
    Mat m;
    m << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
    return m;
  }

  double bin_volume(int bin) const {
    const int k = grid_.lateral_of(bin);
    const double r0 = grid_.lateral_edge(k), r1 = grid_.lateral_edge(k + 1);
    return std::numbers::pi * (r1 * r1 - r0 * r0) * grid_.layer_height();
  }
  double outward_sign(int) const { return 1.0; }  // e_r already points away from the axis

  // Appends the parameters s in (0, 1) where a + s (b - a) crosses the cylinder r = radius:
  // the roots of the quadratic |p + s q|^2 = radius^2 in the xy-plane.
  void lateral_crossings(const VecT& a, const VecT& b, double radius,
                         std::vector<double>& s) const {
    const Eigen::Vector2d p = a.head<2>(), q = (b - a).head<2>();
    const double qq = q.squaredNorm(), pq = p.dot(q);
    const double disc = pq * pq - qq * (p.squaredNorm() - radius * radius);
    if (qq == 0.0 || disc <= 0.0) return;
    const double root = std::sqrt(disc);
    for (double t : {(-pq - root) / qq, (-pq + root) / qq})
      if (t > 0.0 && t < 1.0) s.push_back(t);
  }
  // An interval holding r along the segment: r is at most its larger end value (|.| is convex)
  // and at least the smaller one minus the segment's length.
  std::pair<double, double> lateral_extent(const VecT& a, const VecT& b) const {
    const double ra = lateral(a), rb = lateral(b);
    return {std::max(0.0, std::min(ra, rb) - (b - a).norm()), std::max(ra, rb)};
  }

  // Calls add(bin, volume) for every bin the sphere overlaps, with the exact volume inside
  // (to the accuracy of sphere_cylinder_slab_volume). The volume in ring [r_k, r_k+1] is the
  // difference of the volumes inside the cylinders r_k+1 and r_k, so the rings sum exactly.
  template <class Add>
  void for_each_share(const VecT& centre, double radius, Add&& add) const {
    const double r = lateral(centre), h = height(centre);
    const auto [k0, k1] = grid_.lateral_range(r - radius, r + radius);
    const auto [l0, l1] = grid_.layer_range(h - radius, h + radius);
    if (k0 > k1 || l0 > l1) return;
    const double volume = Dim<3>::volume(radius);
    for (int l = l0; l <= l1; ++l) {
      const double z0 = grid_.normal_edge(l), z1 = grid_.normal_edge(l + 1);
      if (k0 == k1 && h - radius >= z0 && h + radius <= z1 &&
          r - radius >= grid_.lateral_edge(k0) && r + radius <= grid_.lateral_edge(k0 + 1)) {
        add(grid_.bin(k0, l), volume);  // wholly inside one bin: most grains
        continue;
      }
      double inner = sphere_cylinder_slab_volume(r, h, radius, grid_.lateral_edge(k0), z0, z1);
      for (int k = k0; k <= k1; ++k) {
        const double outer =
            sphere_cylinder_slab_volume(r, h, radius, grid_.lateral_edge(k + 1), z0, z1);
        add(grid_.bin(k, l), outer - inner);
        inner = outer;
      }
    }
  }

 private:
  BinGrid grid_;
  double origin_;
};

}  // namespace granjet::analysis
