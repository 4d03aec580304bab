// 2D bin geometry (model §6): layers above the target line x = 0, each cut along y. Lateral
// coordinate y, height h = x - height origin; the local frame is the Cartesian (x, y) one.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

#include "analysis/bin_grid.hpp"
#include "analysis/grain_overlap.hpp"
#include "core/dim.hpp"

namespace granjet::analysis {

class CartesianLayers {
 public:
  static constexpr int kDim = 2;
  using VecT = Vec<2>;
  using Mat = Eigen::Matrix2d;
  static constexpr std::array<std::string_view, 2> kAxes{"x", "y"};
  static constexpr std::array<std::string_view, 2> kCartesianAxes = kAxes;
  static constexpr std::string_view kLateralName = "y";
  static constexpr int kLateral = 1;                 // v_y
  static constexpr int kNormal = 0;                  // v_x
  static constexpr std::array<int, 2> kShear{0, 1};  // sigma_xy of mu* = -sigma_xy/P (model §6)
  static constexpr bool kCurvilinear = false;

  explicit CartesianLayers(const BinSpec& spec)
      : grid_(-spec.target_radius, spec.target_radius, spec.lateral_bins, spec.layer_height,
              spec.layers),
        origin_(spec.height_origin) {}

  const BinGrid& grid() const { return grid_; }
  double lateral(const VecT& x) const { return x.y(); }
  double height(const VecT& x) const { return x.x() - origin_; }
  Mat frame(const VecT&) const { return Mat::Identity(); }

  double bin_volume(int) const { return grid_.lateral_width() * grid_.layer_height(); }
  // The two sides of the jet mirror each other: sigma_xy and D_xy change sign with y. mu*, I_s
  // and eta take them along the outward direction (sign of y) so both sides agree, like r in 3D.
  double outward_sign(int bin) const {
    const int k = grid_.lateral_of(bin);
    return grid_.lateral_edge(k) + grid_.lateral_edge(k + 1) < 0.0 ? -1.0 : 1.0;
  }

  // Appends the s in (0, 1) where a + s (b - a) crosses the line y = edge.
  void lateral_crossings(const VecT& a, const VecT& b, double edge, std::vector<double>& s) const {
    const double dy = b.y() - a.y();
    if (dy == 0.0) return;
    const double t = (edge - a.y()) / dy;
    if (t > 0.0 && t < 1.0) s.push_back(t);
  }
  std::pair<double, double> lateral_extent(const VecT& a, const VecT& b) const {
    return std::minmax(a.y(), b.y());
  }

  // Calls add(bin, area) with the exact area of the disk inside every bin it overlaps.
  template <class Add>
  void for_each_share(const VecT& centre, double radius, Add&& add) const {
    const double y = lateral(centre), h = height(centre);
    const auto [k0, k1] = grid_.lateral_range(y - radius, y + radius);
    const auto [l0, l1] = grid_.layer_range(h - radius, h + radius);
    for (int l = l0; l <= l1; ++l)
      for (int k = k0; k <= k1; ++k)
        add(grid_.bin(k, l),
            disk_rectangle_area(y, h, radius, grid_.lateral_edge(k), grid_.lateral_edge(k + 1),
                                grid_.normal_edge(l), grid_.normal_edge(l + 1)));
  }

 private:
  BinGrid grid_;
  double origin_;
};

}  // namespace granjet::analysis
