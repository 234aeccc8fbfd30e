// Sphere against a plane: one point below the centre.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// A sphere of radius Ra at pa against the plane n.x = d (solid below).
template <class T>
GPUSOLVE_HD Manifold<T> sphere_plane(const math::Vector3<T>& pa, T Ra, const math::Vector3<T>& n, T d) {
  const T height = math::dot(n, pa) - d;
  return one_point<T>(math::Vector3<T>(pa - height * n), n, height - Ra);
}

template <class T>
GPUSOLVE_HD Manifold<T> sphere_plane(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) {
  return within_margin(sphere_plane(a.x, a.p[0], math::Vector3<T>(b.p[0], b.p[1], b.p[2]), b.p[3]), margin);
}

}  // namespace gpusolve::rbd
