// Capsule against a plane: the deepest points of its two end caps.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// A capsule (radius p[0], half length p[1] along its body x) against the plane
// n.x = d (solid below): each end cap's lowest point is a candidate, feature 0
// for the -x end and 1 for the +x end, so a capsule lying flat gets two points.
template <class T>
GPUSOLVE_HD Manifold<T> capsule_plane(const PlacedShape<T>& capsule, const PlacedShape<T>& plane, T margin) {
  using V = math::Vector3<T>;
  const V n(plane.p[0], plane.p[1], plane.p[2]);
  const T d = plane.p[3], r = capsule.p[0], L = capsule.p[1];
  const V u = capsule.axis(0);
  Manifold<T> m;
  m.n = n;
  for (int k = 0; k < 2; ++k) {
    const V e = capsule.x + (k == 0 ? -L : L) * u;
    const T height = math::dot(n, e) - d;
    const T gap = height - r;
    if (gap < margin) m.add(V(e + (gap / 2 - height) * n), gap, std::uint32_t(k));
  }
  return m;
}

}  // namespace gpusolve::rbd
