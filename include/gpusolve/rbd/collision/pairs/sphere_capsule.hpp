// Sphere against a capsule: one point on the line from the core segment to the centre.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/segment.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// A sphere (radius p[0]) against a capsule (radius p[0], half length p[1] along
// its body x): a sphere against the core's closest point, feature 0. A centre
// on the core is pushed out perpendicular to the capsule's axis.
template <class T>
GPUSOLVE_HD Manifold<T> sphere_capsule(const PlacedShape<T>& sphere, const PlacedShape<T>& capsule, T margin) {
  using V = math::Vector3<T>;
  const T rs = sphere.p[0], rc = capsule.p[0], L = capsule.p[1];
  const V u = capsule.axis(0);
  const V e0 = capsule.x - L * u, e1 = capsule.x + L * u;
  const V c = segment_closest_point(e0, e1, sphere.x);
  const V d = sphere.x - c;
  const T dist = math::norm(d);
  const V n = dist > T(1e-7) * (rs + rc + L) ? V(d * (T(1) / dist)) : unit_perpendicular(u);
  return within_margin(one_point<T>(V(c + rc * n), n, math::dot(d, n) - rs - rc, 0u), margin);
}

}  // namespace gpusolve::rbd
