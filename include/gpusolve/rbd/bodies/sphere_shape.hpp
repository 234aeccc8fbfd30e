// The sphere: parameters (radius, 0, 0, 0).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"
#include "gpusolve/rbd/bodies/solid_properties.hpp"

namespace gpusolve::rbd {

// A solid sphere of radius r: I = 2/5 m r^2 about every axis.
template <class T>
SolidProperties<T> solid_sphere(T r, T mass) {
  const T I = T(2) / T(5) * mass * r * r;
  return {T(4 * pi / 3) * r * r * r, {I, I, I}};
}

template <>
struct ShapeTraits<sphere> {
  static constexpr const char* name = "sphere";
  static constexpr std::size_t params = 1;
  static constexpr bool rotated = false;  // a turn leaves its surface where it was
  static constexpr bool part = true;
  static constexpr bool moves = true;

  template <class T>
  GPUSOLVE_HD static T bound(T r, T, T) {
    return r;
  }
  template <class T>
  GPUSOLVE_HD static T feature(T r, T, T) {
    return r;
  }
  template <class T>
  static void validate(const std::array<T, shape_param_rows>& p, std::size_t body, const std::string& prefix) {
    if (!(p[0] > 0)) throw InvalidBodyError(body, prefix + "radius", "must be positive");
  }
  template <class T>
  static SolidProperties<T> solid(const std::array<T, shape_param_rows>& p, T mass) {
    return solid_sphere(p[0], mass);
  }
};

}  // namespace gpusolve::rbd
