// The box: parameters (half extents along the body's x, y, z, 0).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"
#include "gpusolve/rbd/bodies/solid_properties.hpp"

namespace gpusolve::rbd {

// A solid box of half extents h: I_x = m (h_y^2 + h_z^2) / 3, and so on.
template <class T>
SolidProperties<T> solid_box(const std::array<T, 3>& h, T mass) {
  const T x = h[0] * h[0], y = h[1] * h[1], z = h[2] * h[2];
  return {8 * h[0] * h[1] * h[2], {mass * (y + z) / 3, mass * (x + z) / 3, mass * (x + y) / 3}};
}

template <>
struct ShapeTraits<box> {
  static constexpr const char* name = "box";
  static constexpr std::size_t params = 3;
  static constexpr bool rotated = true;
  static constexpr bool part = true;
  static constexpr bool moves = true;

  // Its half diagonal.
  template <class T>
  GPUSOLVE_HD static T bound(T x, T y, T z) {
    return std::sqrt(x * x + y * y + z * z);
  }
  // Its smallest half extent.
  template <class T>
  GPUSOLVE_HD static T feature(T x, T y, T z) {
    const T xy = x < y ? x : y;
    return xy < z ? xy : z;
  }
  template <class T>
  static void validate(const std::array<T, shape_param_rows>& p, std::size_t body, const std::string& prefix) {
    for (int k = 0; k < 3; ++k)
      if (!(p[k] > 0)) throw InvalidBodyError(body, prefix + "half_extents", "must be positive");
  }
  template <class T>
  static SolidProperties<T> solid(const std::array<T, shape_param_rows>& p, T mass) {
    return solid_box<T>({p[0], p[1], p[2]}, mass);
  }
};

}  // namespace gpusolve::rbd
