// Contact reduction: at most four of a face contact's candidate points.
#pragma once

#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"

namespace gpusolve::rbd {

namespace detail {

inline constexpr int max_candidates = 8;  // a quad clipped by four sides

// Among the candidates within `tie` of the best by key[k] (smaller is better),
// the one of the smallest feature id. The depths of a face lying flat, and the
// spans of a symmetric polygon, differ by rounding and by tilts that change
// from step to step; the ids do not, so the same points are kept and the warm
// start finds them. -1 if no key is below `none`.
template <class T>
GPUSOLVE_HD int first_of_best(const ManifoldPoint<T>* c, int n, T none, T tie, const T* key) {
  T low = none;
  for (int k = 0; k < n; ++k) low = key[k] < low ? key[k] : low;
  int best = -1;
  for (int k = 0; k < n; ++k)
    if (key[k] < none && key[k] <= low + tie && (best < 0 || c[k].feature < c[best].feature)) best = k;
  return best;
}

// The candidate with the largest score(k) above floor, near ties (1e-4
// relative) going to the smaller feature id.
template <class T, class Score>
GPUSOLVE_HD int best_point(const ManifoldPoint<T>* c, int n, T floor, const Score& score) {
  T key[max_candidates], top = floor;
  for (int k = 0; k < n; ++k) {
    key[k] = -score(k);
    top = -key[k] > top ? -key[k] : top;
  }
  return first_of_best(c, n, -floor, T(1e-4) * (top < T(0) ? -top : top), key);
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
  // The deepest, near ties (a ten-thousandth of the candidates' span) going to
  // the smaller feature id.
  T span2 = 0, gap[detail::max_candidates];
  for (int k = 0; k < n; ++k) {
    const T d2 = math::sqr_norm(math::Vector3<T>(c[k].p - c[0].p));
    span2 = d2 > span2 ? d2 : span2;
    gap[k] = c[k].gap;
  }
  const int i0 = detail::first_of_best(c, n, std::numeric_limits<T>::max(), T(1e-4) * std::sqrt(span2), gap);
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
  T left[detail::max_candidates];  // twice the signed area of (i0, i1, k), once for both sides
  for (int k = 0; k < n; ++k) left[k] = math::dot(math::Vector3<T>(diag % math::Vector3<T>(c[k].p - c[i0].p)), normal);
  const int i2 = detail::best_point(c, n, floor, [&](int k) { return left[k]; });
  const int i3 = detail::best_point(c, n, floor, [&](int k) { return -left[k]; });
  if (i2 >= 0) m.add(c[i2].p, c[i2].gap, c[i2].feature);
  if (i3 >= 0) m.add(c[i3].p, c[i3].gap, c[i3].feature);
  return m;
}

}  // namespace gpusolve::rbd
