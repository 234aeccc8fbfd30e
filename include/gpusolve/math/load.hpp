// load3(), load9(): element i of a structure-of-arrays field (3 or 9 rows)
// copied into a Vector3 or a Matrix3x3 value, each entry read once.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/matrix3x3.hpp"
#include "gpusolve/math/vector3.hpp"

namespace gpusolve::math {

template <class T, class V>
GPUSOLVE_HD Vector3<T> load3(const V& v, std::size_t i) {
  return Vector3<T>(v(i, 0), v(i, 1), v(i, 2));
}
template <class T, class V>
GPUSOLVE_HD Matrix3x3<T> load9(const V& v, std::size_t i) {
  return Matrix3x3<T>(v(i, 0), v(i, 1), v(i, 2), v(i, 3), v(i, 4), v(i, 5), v(i, 6), v(i, 7), v(i, 8));
}

}  // namespace gpusolve::math
