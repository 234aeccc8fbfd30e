// PlacedShape: one primitive where it is in the world, as the narrow phase reads it.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd {

// A primitive's pose (centre x and rotation R, body -> world) and its shape
// parameters p (shapes.hpp): sphere (r), box (hx, hy, hz), capsule (r, half
// length along the body x axis), plane (nx, ny, nz, d) in the world frame.
template <class T>
struct PlacedShape {
  math::Vector3<T> x;
  math::Matrix3x3<T> R;
  T p[4];

  // Column k of R: the body's axis k in the world frame.
  GPUSOLVE_HD math::Vector3<T> axis(int k) const { return {R(0, k), R(1, k), R(2, k)}; }
  // A world point in the shape's frame, and back.
  GPUSOLVE_HD math::Vector3<T> to_local(const math::Vector3<T>& w) const {
    return math::Vector3<T>(math::transpose(R) * (w - x));
  }
  GPUSOLVE_HD math::Vector3<T> to_world(const math::Vector3<T>& l) const { return math::Vector3<T>(x + R * l); }
};

}  // namespace gpusolve::rbd
