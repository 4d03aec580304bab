// A plain vector of W doubles with the arithmetic the contact laws use, spelled like Eigen's
// (dot, squaredNorm, Zero) so that each law is written once for both. The force pass runs
// the law on these over per-contact columns (soft_dem/contact_table.hpp): GCC vectorises that
// loop, several contacts per register, but not one over Eigen's fixed-size vectors, whose
// copies stay in memory and whose own SSE code for 2-vectors blocks its loop vectoriser.
#pragma once

#include <cstdint>

namespace granjet::dem {

template <int W>
struct LaneVec {
  double c[W];

  static LaneVec Zero() { return {}; }
  // Element i of an array of W-vectors seen as plain doubles (base[W i + d], an address
  // form GCC's vectoriser can gather from; through Eigen's members it cannot).
  static LaneVec at(const double* base, std::int64_t i) {
    LaneVec v;
    for (int d = 0; d < W; ++d) v.c[d] = base[W * i + d];
    return v;
  }
  double operator[](int d) const { return c[d]; }
  double& operator[](int d) { return c[d]; }
  // Summed in Eigen's order ((x0 y0 + x1 y1) + x2 y2): the same roundings as Vec<D>.
  double dot(const LaneVec& o) const {
    double sum = c[0] * o.c[0];
    for (int d = 1; d < W; ++d) sum += c[d] * o.c[d];
    return sum;
  }
  double squaredNorm() const { return dot(*this); }

  LaneVec& operator+=(const LaneVec& o) {
    for (int d = 0; d < W; ++d) c[d] += o.c[d];
    return *this;
  }
  LaneVec& operator-=(const LaneVec& o) {
    for (int d = 0; d < W; ++d) c[d] -= o.c[d];
    return *this;
  }
  friend LaneVec operator+(LaneVec a, const LaneVec& b) { return a += b; }
  friend LaneVec operator-(LaneVec a, const LaneVec& b) { return a -= b; }
  friend LaneVec operator-(LaneVec a) {
    for (int d = 0; d < W; ++d) a.c[d] = -a.c[d];
    return a;
  }
  friend LaneVec operator*(double s, LaneVec a) {
    for (int d = 0; d < W; ++d) a.c[d] = s * a.c[d];
    return a;
  }
  friend LaneVec operator*(LaneVec a, double s) { return s * a; }
};

// Cross products as Dim<D>::cross and spin_cross: the out-of-plane component in 2D (a spin is
// a scalar there), Eigen's formula in 3D.
inline double cross(const LaneVec<2>& a, const LaneVec<2>& b) {
  return a.c[0] * b.c[1] - a.c[1] * b.c[0];
}
inline LaneVec<3> cross(const LaneVec<3>& a, const LaneVec<3>& b) {
  return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2],
           a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}
inline LaneVec<2> spin_cross(double w, const LaneVec<2>& r) { return {{-w * r.c[1], w * r.c[0]}}; }
inline LaneVec<3> spin_cross(const LaneVec<3>& w, const LaneVec<3>& r) { return cross(w, r); }

}  // namespace granjet::dem
