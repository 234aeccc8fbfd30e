// Capsule against capsule: the closest points of the core segments, or the two
// ends of their overlap where the capsules lie side by side.
#pragma once

#include <cmath>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/segment.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

namespace detail {

// Which feature of a capsule a core parameter names: 0 the start cap, 1 the end cap, 2 the side.
template <class T>
GPUSOLVE_HD std::uint32_t capsule_part(T s) {
  return s <= T(0) ? 0u : (s >= T(1) ? 1u : 2u);
}

}  // namespace detail

// Capsules a and b (radius p[0], half length p[1] along body x). One point at
// the cores' closest points, feature 3 * part(a) + part(b) (caps 0, 1, side 2).
// Cores within about 8 degrees of parallel whose projections overlap give two
// points instead, at the overlap's ends measured along a (features 0, 1), each
// with its own gap along the shared normal: a capsule lying on another rests
// on both. Meeting cores take the normal across both axes (or any
// perpendicular to a's axis when parallel), turned to point from b to a.
template <class T>
GPUSOLVE_HD Manifold<T> capsule_capsule(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) {
  using V = math::Vector3<T>;
  const T ra = a.p[0], La = a.p[1], rb = b.p[0], Lb = b.p[1];
  const V ua = a.axis(0), ub = b.axis(0);
  const V a0 = a.x - La * ua, a1 = a.x + La * ua;
  const V b0 = b.x - Lb * ub, b1 = b.x + Lb * ub;
  const T scale = ra + rb + La + Lb;
  const SegmentClosest<T> cp = segment_segment_closest(a0, a1, b0, b1);
  const V d = cp.c1 - cp.c2;
  const T dist = math::norm(d);
  V n;
  if (dist > T(1e-6) * scale) {
    n = d * (T(1) / dist);
  } else {
    const V c = ua % ub;
    const T len = math::norm(c);
    n = len > T(1e-3) ? V(c * (T(1) / len)) : unit_perpendicular(ua);
    const V ab = a.x - b.x;
    if (math::dot(n, ab) < T(0)) n = -n;
  }

  if (std::fabs(math::dot(ua, ub)) > T(0.99)) {
    // b's ends projected on a's axis, the interval clipped to a's core.
    const V ab0 = b0 - a.x, ab1 = b1 - a.x;
    const T s0 = math::dot(ab0, ua), s1 = math::dot(ab1, ua);
    const T lo = s0 < s1 ? (s0 > -La ? s0 : -La) : (s1 > -La ? s1 : -La);
    const T hi = s0 < s1 ? (s1 < La ? s1 : La) : (s0 < La ? s0 : La);
    if (hi - lo > T(1e-3) * scale) {
      Manifold<T> m;
      m.n = n;
      for (int k = 0; k < 2; ++k) {
        const V pa = a.x + (k == 0 ? lo : hi) * ua;
        const V pb = segment_closest_point(b0, b1, pa);
        const V dk = pa - pb;
        const T gap = math::dot(dk, n) - ra - rb;
        if (gap < margin) m.add(V(pb + (rb + gap / 2) * n), gap, std::uint32_t(k));
      }
      return m;
    }
  }
  const std::uint32_t feature = 3u * detail::capsule_part(cp.s) + detail::capsule_part(cp.t);
  return within_margin(one_point<T>(V(cp.c2 + rb * n), n, math::dot(d, n) - ra - rb, feature), margin);
}

}  // namespace gpusolve::rbd
