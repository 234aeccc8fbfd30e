// Contact reduction: at most four of a face contact's candidate points.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"

namespace gpusolve::rbd {

namespace detail {

// The candidate with the largest score(k) above floor; near ties (1e-4
// relative) go to the deeper point, so exact ties resolve the same way every step.
template <class T, class Score>
GPUSOLVE_HD int best_point(const ManifoldPoint<T>* c, int n, T floor, const Score& score) {
  int best = -1;
  T bs = floor;
  for (int k = 0; k < n; ++k) {
    const T s = score(k);
    if (!(s > floor)) continue;
    const T tol = T(1e-4) * (bs < T(0) ? -bs : bs);
    if (best < 0 || s > bs + tol || (s >= bs - tol && c[k].gap < c[best].gap)) {
      best = k;
      bs = s;
    }
  }
  return best;
}

}  // namespace detail

// The manifold (normal n) of n candidates c, kept whole up to four; beyond, the
// deepest, the one farthest from it across the contact plane, and the two
// spanning the largest triangles on either side of that diagonal (Jolt, Bullet).
template <class T>
GPUSOLVE_HD Manifold<T> reduce_to_four(const ManifoldPoint<T>* c, int n, const math::Vector3<T>& normal) {
  Manifold<T> m;
  m.n = normal;
  if (n <= max_manifold_points) {
    for (int k = 0; k < n; ++k) m.add(c[k].p, c[k].gap, c[k].feature);
    return m;
  }
  int i0 = 0;
  for (int k = 1; k < n; ++k)
    if (c[k].gap < c[i0].gap) i0 = k;
  m.add(c[i0].p, c[i0].gap, c[i0].feature);
  const auto across = [&](int k) -> T {  // squared distance from c[i0] in the contact plane
    const math::Vector3<T> d = c[k].p - c[i0].p;
    const math::Vector3<T> t = d - math::dot(d, normal) * normal;
    return math::dot(t, t);
  };
  const int i1 = detail::best_point(c, n, T(0), across);
  if (i1 < 0) return m;  // all candidates at one place
  m.add(c[i1].p, c[i1].gap, c[i1].feature);
  const math::Vector3<T> diag = c[i1].p - c[i0].p;
  const T floor = T(1e-6) * across(i1);  // twice the area of a triangle worth keeping
  const auto left = [&](int k) -> T {
    const math::Vector3<T> d = c[k].p - c[i0].p;
    return math::dot(math::Vector3<T>(diag % d), normal);
  };
  const auto right = [&](int k) -> T { return -left(k); };
  const int i2 = detail::best_point(c, n, floor, left);
  const int i3 = detail::best_point(c, n, floor, right);
  if (i2 >= 0) m.add(c[i2].p, c[i2].gap, c[i2].feature);
  if (i3 >= 0) m.add(c[i3].p, c[i3].gap, c[i3].feature);
  return m;
}

}  // namespace gpusolve::rbd
