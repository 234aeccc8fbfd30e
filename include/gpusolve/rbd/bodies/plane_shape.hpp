// The plane: parameters (unit normal x, y, z, offset d) in the world frame;
// the points x with n.x = d lie on it, the half-space n.x < d is solid. It is
// always fixed and has no mass.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"

namespace gpusolve::rbd {

template <>
struct ShapeTraits<plane> {
  static constexpr const char* name = "plane";
  static constexpr std::size_t params = 4;
  static constexpr bool rotated = false;  // its parameters are in the world frame
  static constexpr bool part = false;
  static constexpr bool moves = false;

  // It bounds nothing; a body on it is measured against the body.
  template <class T>
  GPUSOLVE_HD static T bound(T, T, T) {
    return std::numeric_limits<T>::infinity();
  }
  template <class T>
  GPUSOLVE_HD static T feature(T, T, T) {
    return std::numeric_limits<T>::infinity();
  }
  template <class T>
  static void validate(const std::array<T, shape_param_rows>& p, std::size_t body, const std::string& prefix) {
    const T nn = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
    if (std::abs(nn - T(1)) > T(1e-4)) throw InvalidBodyError(body, prefix + "normal", "must have unit length");
  }
};

}  // namespace gpusolve::rbd
