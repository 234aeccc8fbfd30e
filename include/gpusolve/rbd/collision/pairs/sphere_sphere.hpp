// Sphere against sphere: one point on the line of centres.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// Spheres of radii Ra at pa and Rb at pb, whatever their gap. Coincident
// centres get the normal +z.
template <class T>
GPUSOLVE_HD Manifold<T> sphere_sphere(const math::Vector3<T>& pa, T Ra, const math::Vector3<T>& pb, T Rb) {
  const math::Vector3<T> d = pa - pb;
  const T dist = math::norm(d);
  const math::Vector3<T> n = dist > T(0) ? math::Vector3<T>(d * (T(1) / dist)) : math::Vector3<T>(T(0), T(0), T(1));
  return one_point<T>(math::Vector3<T>(pb + Rb * n), n, dist - Ra - Rb);
}

// The table's entry: the point where the gap is below the margin.
template <class T>
GPUSOLVE_HD Manifold<T> sphere_sphere(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) {
  return within_margin(sphere_sphere(a.x, a.p[0], b.x, b.p[0]), margin);
}

}  // namespace gpusolve::rbd
