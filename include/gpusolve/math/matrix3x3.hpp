// Matrix3x3<T>: a row-major 3x3 matrix holding its elements, usable in expressions.
#pragma once

#include <cstddef>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/value.hpp"

namespace gpusolve::math {

template <class T>
class Matrix3x3 : public detail::Value<Matrix3x3<T>, MatrixKind, T> {
  using Base = detail::Value<Matrix3x3<T>, MatrixKind, T>;

 public:
  using Base::Base;
  using Base::operator=;

  Matrix3x3() = default;  // zero
  GPUSOLVE_HD Matrix3x3(T xx, T xy, T xz, T yx, T yy, T yz, T zx, T zy, T zz)
      : Base({xx, xy, xz, yx, yy, yz, zx, zy, zz}) {}

  GPUSOLVE_HD static Matrix3x3 diagonal(T x, T y, T z) { return {x, 0, 0, 0, y, 0, 0, 0, z}; }
  GPUSOLVE_HD static Matrix3x3 identity() { return diagonal(1, 1, 1); }

  GPUSOLVE_HD T operator()(std::size_t r, std::size_t c) const { return (*this)[3 * r + c]; }
  GPUSOLVE_HD T& operator()(std::size_t r, std::size_t c) { return (*this)[3 * r + c]; }
};

static_assert(std::is_trivially_copyable_v<Matrix3x3<float>>);

}  // namespace gpusolve::math
