// Quaternion<T>: a quaternion (w, x, y, z) holding its elements, usable in expressions.
#pragma once

#include <cmath>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/value.hpp"

namespace gpusolve::math {

template <class T>
class Quaternion : public detail::Value<Quaternion<T>, QuaternionKind, T> {
  using Base = detail::Value<Quaternion<T>, QuaternionKind, T>;

 public:
  using Base::Base;
  using Base::operator=;

  Quaternion() = default;  // zero; the rotation "none" is identity()
  GPUSOLVE_HD Quaternion(T w, T x, T y, T z) : Base({w, x, y, z}) {}

  GPUSOLVE_HD static Quaternion identity() { return {1, 0, 0, 0}; }

  // The rotation by `angle` (radians) about the unit vector `axis`.
  template <class A>
  GPUSOLVE_HD static Quaternion from_axis_angle(const Expr<A, VectorKind, T>& axis, T angle) {
    const T s = std::sin(angle / 2);
    const A& u = axis.derived();
    return {std::cos(angle / 2), s * u[0], s * u[1], s * u[2]};
  }
};

static_assert(std::is_trivially_copyable_v<Quaternion<float>>);

}  // namespace gpusolve::math
