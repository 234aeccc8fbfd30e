// Box against a plane: the box's vertices within the margin of the plane.
#pragma once

#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/reduce_points.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// A box (half extents p[0..2]) against the plane n.x = d (b.p, solid below):
// one point per vertex whose height is below the margin, normal n, feature =
// vertex index (bit k set: the + side of axis k); past four, reduce_to_four.
template <class T>
GPUSOLVE_HD Manifold<T> box_plane(const PlacedShape<T>& box, const PlacedShape<T>& plane, T margin) {
  const math::Vector3<T> n(plane.p[0], plane.p[1], plane.p[2]);
  ManifoldPoint<T> c[8];
  int count = 0;
  for (std::uint32_t v = 0; v < 8; ++v) {
    math::Vector3<T> l;
    for (int k = 0; k < 3; ++k) l[k] = (v >> k) & 1u ? box.p[k] : -box.p[k];
    const math::Vector3<T> w = box.to_world(l);
    const T gap = math::dot(n, w) - plane.p[3];
    if (gap < margin) c[count++] = {math::Vector3<T>(w - (gap / 2) * n), gap, v};
  }
  return reduce_to_four(c, count, n);
}

}  // namespace gpusolve::rbd
