// The capsule: parameters (radius, half length, 0, 0), the points within the
// radius of the segment from -half length to +half length along the body's x axis.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"
#include "gpusolve/rbd/bodies/solid_properties.hpp"

namespace gpusolve::rbd {

// Radius r, core segment of half length L along x: a cylinder of length 2L
// and two hemispheres, the mass shared by volume; each hemisphere's centre of
// mass lies 3r/8 beyond the segment's end.
template <class T>
SolidProperties<T> solid_capsule(T r, T L, T mass) {
  const T H = 2 * L;
  const T cylinder = T(pi) * r * r * H, balls = T(4 * pi / 3) * r * r * r;
  const T mc = mass * cylinder / (cylinder + balls), ms = mass - mc;
  const T axial = mc * r * r / 2 + ms * T(2) / T(5) * r * r;
  const T across = mc * (r * r / 4 + H * H / 12) + ms * (T(2) / T(5) * r * r + H * H / 4 + T(3) / T(8) * H * r);
  return {cylinder + balls, {axial, across, across}};
}

template <>
struct ShapeTraits<capsule> {
  static constexpr const char* name = "capsule";
  static constexpr std::size_t params = 2;
  static constexpr bool rotated = true;
  static constexpr bool part = true;
  static constexpr bool moves = true;

  template <class T>
  GPUSOLVE_HD static T bound(T r, T half_length, T) {
    return r + half_length;
  }
  template <class T>
  GPUSOLVE_HD static T feature(T r, T, T) {
    return r;
  }
  template <class T>
  static void validate(const std::array<T, shape_param_rows>& p, std::size_t body, const std::string& prefix) {
    if (!(p[0] > 0)) throw InvalidBodyError(body, prefix + "radius", "must be positive");
    if (!(p[1] > 0)) throw InvalidBodyError(body, prefix + "half_length", "must be positive (a sphere has none)");
  }
  template <class T>
  static SolidProperties<T> solid(const std::array<T, shape_param_rows>& p, T mass) {
    return solid_capsule(p[0], p[1], mass);
  }
};

}  // namespace gpusolve::rbd
