// Rotations: a vector rotated by a quaternion, quaternion <-> rotation matrix,
// and the orientation update for an angular velocity over a time step.
#pragma once

#include <cfloat>
#include <cmath>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/matrix3x3.hpp"
#include "gpusolve/math/norm.hpp"
#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/quaternion_expr.hpp"
#include "gpusolve/math/vector3.hpp"
#include "gpusolve/math/vector_expr.hpp"

namespace gpusolve::math {

// q v q* for a unit quaternion q, as v + w t + u x t with u = (x, y, z), t = 2 u x v.
template <class Q, class V, class T>
GPUSOLVE_HD Vector3<T> rotate(const QuaternionExpr<Q, T>& q, const VectorExpr<V, T>& v) {
  const Quaternion<T> p(q);  // each element read once
  const Vector3<T> u(p[1], p[2], p[3]), x(v);
  const Vector3<T> t = T(2) * (u % x);
  return x + p[0] * t + u % t;
}

// The rotation matrix of a unit quaternion.
template <class Q, class T>
GPUSOLVE_HD Matrix3x3<T> to_rotation_matrix(const QuaternionExpr<Q, T>& q) {
  const Quaternion<T> p(q);
  const T w = p[0], x = p[1], y = p[2], z = p[3];
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

// The unit quaternion of a rotation matrix (one of q, -q). Shepperd's method:
// the square root is taken of the largest of 4w^2, 4x^2, 4y^2, 4z^2, so no
// division by a small number loses precision.
template <class M, class T>
GPUSOLVE_HD Quaternion<T> to_quaternion(const MatrixExpr<M, T>& m) {
  const Matrix3x3<T> r(m);
  const T trace = r(0, 0) + r(1, 1) + r(2, 2);
  if (trace >= r(0, 0) && trace >= r(1, 1) && trace >= r(2, 2)) {
    const T s = 2 * std::sqrt(1 + trace);  // 4w
    return {s / 4, (r(2, 1) - r(1, 2)) / s, (r(0, 2) - r(2, 0)) / s, (r(1, 0) - r(0, 1)) / s};
  }
  if (r(0, 0) >= r(1, 1) && r(0, 0) >= r(2, 2)) {
    const T s = 2 * std::sqrt(1 + r(0, 0) - r(1, 1) - r(2, 2));  // 4x
    return {(r(2, 1) - r(1, 2)) / s, s / 4, (r(0, 1) + r(1, 0)) / s, (r(0, 2) + r(2, 0)) / s};
  }
  if (r(1, 1) >= r(2, 2)) {
    const T s = 2 * std::sqrt(1 + r(1, 1) - r(0, 0) - r(2, 2));  // 4y
    return {(r(0, 2) - r(2, 0)) / s, (r(0, 1) + r(1, 0)) / s, s / 4, (r(1, 2) + r(2, 1)) / s};
  }
  const T s = 2 * std::sqrt(1 + r(2, 2) - r(0, 0) - r(1, 1));  // 4z
  return {(r(1, 0) - r(0, 1)) / s, (r(0, 2) + r(2, 0)) / s, (r(1, 2) + r(2, 1)) / s, s / 4};
}

// The orientation after turning at angular velocity w (world frame) for dt:
// normalize(from_axis_angle(w / |w|, |w| dt) * q), the exact exponential map.
template <class Q, class W, class T>
GPUSOLVE_HD Quaternion<T> integrate_orientation(const QuaternionExpr<Q, T>& q,
                                                const VectorExpr<W, T>& w, T dt) {
  const Vector3<T> omega(w);
  const T speed = norm(omega), half = speed * dt / 2;
  // sin(half) / |w| tends to dt / 2 as |w| -> 0. Below the threshold its Taylor
  // series dt/2 (1 - half^2/6) is exact to rounding (the next term, half^4/120,
  // is under epsilon) and never divides by a vanishing |w|.
  constexpr T eps = std::is_same_v<T, float> ? FLT_EPSILON : DBL_EPSILON;
  const T h2 = half * half;
  const T s = h2 * h2 < 120 * eps ? dt / 2 * (1 - h2 / 6) : std::sin(half) / speed;
  const Quaternion<T> turn(std::cos(half), s * omega[0], s * omega[1], s * omega[2]);
  const Quaternion<T> p = turn * q;
  return normalize(p);
}

}  // namespace gpusolve::math
