// Vector3<T>: a 3-vector holding its elements, usable in expressions.
#pragma once

#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/value.hpp"

namespace gpusolve::math {

template <class T>
class Vector3 : public detail::Value<Vector3<T>, VectorKind, T> {
  using Base = detail::Value<Vector3<T>, VectorKind, T>;

 public:
  using Base::Base;
  using Base::operator=;

  Vector3() = default;  // zero
  GPUSOLVE_HD Vector3(T x, T y, T z) : Base({x, y, z}) {}
};

static_assert(std::is_trivially_copyable_v<Vector3<float>>);

}  // namespace gpusolve::math
