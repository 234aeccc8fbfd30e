// Sphere against a box: one point at the box's closest surface point.
#pragma once

#include <cmath>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// A sphere of radius Ra at pa against a box (half extents p[0..2]). Outside
// the box the normal runs from the closest point of the box (on a face, edge
// or corner) to the centre; a centre inside is pushed out through the nearest face.
template <class T>
GPUSOLVE_HD Manifold<T> sphere_box(const math::Vector3<T>& pa, T Ra, const PlacedShape<T>& box) {
  const math::Vector3<T> c = box.to_local(pa);
  const T h[3] = {box.p[0], box.p[1], box.p[2]};
  math::Vector3<T> q;
  for (int k = 0; k < 3; ++k) q[k] = c[k] < -h[k] ? -h[k] : (c[k] > h[k] ? h[k] : c[k]);
  const math::Vector3<T> out = c - q;
  const T dist = math::norm(out);
  math::Vector3<T> n_local;
  T depth;  // signed distance of the centre from the box surface
  if (dist > T(0)) {
    n_local = out * (T(1) / dist);
    depth = dist;
  } else {
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (h[j] - std::fabs(c[j]) < h[k] - std::fabs(c[k])) k = j;
    const T s = c[k] < T(0) ? T(-1) : T(1);
    n_local[k] = s;
    q[k] = s * h[k];
    depth = -(h[k] - std::fabs(c[k]));
  }
  return one_point<T>(box.to_world(q), math::Vector3<T>(box.R * n_local), depth - Ra);
}

template <class T>
GPUSOLVE_HD Manifold<T> sphere_box(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) {
  return within_margin(sphere_box(a.x, a.p[0], b), margin);
}

}  // namespace gpusolve::rbd
