// Dimension traits: every difference between 2D and 3D lives here, not in kernels.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <numbers>
#include <type_traits>

namespace granjet {

template <int D>
struct Dim;

template <>
struct Dim<2> {
  static constexpr int kDim = 2;
  using Vec = Eigen::Vector2d;
  using Spin = double;  // angular velocity about the out-of-plane axis
  // Moment of inertia of a solid disk: I = 1/2 m R^2 (model §2).
  static constexpr double kInertiaFactor = 0.5;
  static double volume(double radius) { return std::numbers::pi * radius * radius; }
  static Spin zero_spin() { return 0.0; }
  // 2D cross products: the z component of a x b, and w x r for a spin along z.
  static Spin cross(const Vec& a, const Vec& b) { return a.x() * b.y() - a.y() * b.x(); }
  static Vec spin_cross(Spin w, const Vec& r) { return Vec(-w * r.y(), w * r.x()); }
  static double spin_dot(Spin a, Spin b) { return a * b; }
};

template <>
struct Dim<3> {
  static constexpr int kDim = 3;
  using Vec = Eigen::Vector3d;
  using Spin = Eigen::Vector3d;
  // Moment of inertia of a solid sphere: I = 2/5 m R^2 (model §2).
  static constexpr double kInertiaFactor = 0.4;
  static double volume(double radius) {
    return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  }
  static Spin zero_spin() { return Spin::Zero(); }
  static Spin cross(const Vec& a, const Vec& b) { return a.cross(b); }
  static Vec spin_cross(const Spin& w, const Vec& r) { return w.cross(r); }
  static double spin_dot(const Spin& a, const Spin& b) { return a.dot(b); }
};

template <int D>
using Vec = typename Dim<D>::Vec;
template <int D>
using Spin = typename Dim<D>::Spin;

// Calls f(std::integral_constant<int, D>{}) for the run-time dimension (2 or 3): the one place
// where a scene's or a file's dimension becomes a template parameter.
template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  if (dimension == 2) return f(std::integral_constant<int, 2>{});
  return f(std::integral_constant<int, 3>{});
}

}  // namespace granjet
