// Capsule against a box: the exact closest points of the core segment and the
// box while they are apart, the axis of least penetration once the core is in;
// two points where the capsule lies along a face.
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

// Squared distance from the point P0 + t D to the box |x_k| <= h_k.
template <class T>
GPUSOLVE_HD T capsule_box_dist2(const math::Vector3<T>& P0, const math::Vector3<T>& D, const T h[3], T t) {
  T s = T(0);
  for (int k = 0; k < 3; ++k) {
    const T x = P0[k] + t * D[k];
    const T o = x > h[k] ? x - h[k] : (x < -h[k] ? x + h[k] : T(0));
    s += o * o;
  }
  return s;
}

// The t in [0, 1] minimising the distance from P0 + t D to the box. The squared
// distance is convex and piecewise quadratic, with breaks where a coordinate
// crosses +-h_k: minimise each piece exactly and keep the best (no iteration).
template <class T>
GPUSOLVE_HD T capsule_box_closest_param(const math::Vector3<T>& P0, const math::Vector3<T>& D, const T h[3]) {
  T ts[8];
  int n = 0;
  ts[n++] = T(0);
  for (int k = 0; k < 3; ++k)
    if (D[k] != T(0))
      for (int side = 0; side < 2; ++side) {
        const T t = ((side == 0 ? -h[k] : h[k]) - P0[k]) / D[k];
        if (t > T(0) && t < T(1)) ts[n++] = t;
      }
  ts[n++] = T(1);
  for (int i = 1; i < n; ++i)  // insertion sort, at most 8 values
    for (int j = i; j > 0 && ts[j] < ts[j - 1]; --j) {
      const T tmp = ts[j];
      ts[j] = ts[j - 1];
      ts[j - 1] = tmp;
    }
  T best_t = T(0), best = capsule_box_dist2(P0, D, h, T(0));
  for (int i = 0; i + 1 < n; ++i) {
    const T ta = ts[i], tb = ts[i + 1];
    if (!(tb > ta)) continue;
    const T mid = (ta + tb) / 2;
    T A = T(0), B = T(0);  // the piece is sum (D_k t + b_k)^2 over the coordinates outside
    for (int k = 0; k < 3; ++k) {
      const T x = P0[k] + mid * D[k];
      if (x > h[k] || x < -h[k]) {
        const T bk = P0[k] - (x > h[k] ? h[k] : -h[k]);
        A += D[k] * D[k];
        B += D[k] * bk;
      }
    }
    const T t = A > T(0) ? clamp_to(-B / A, ta, tb) : mid;
    const T d2 = capsule_box_dist2(P0, D, h, t);
    if (d2 < best) {
      best = d2;
      best_t = t;
    }
  }
  return best_t;
}

}  // namespace detail

// A capsule (radius p[0], half length p[1] along its body x) against a box
// (half extents p[0..2]), worked in the box frame. Feature ids: 0 and 1 for the
// core's -x and +x ends (or the two ends of the core clipped to a face), 2 for a
// point inside the core (across an edge). A core parallel to a face within
// about 6 degrees, with the face's normal, is clipped to the face rectangle
// and gives both clipped ends, each with its own gap.
template <class T>
GPUSOLVE_HD Manifold<T> capsule_box(const PlacedShape<T>& capsule, const PlacedShape<T>& box, T margin) {
  using V = math::Vector3<T>;
  const T r = capsule.p[0], L = capsule.p[1];
  const T h[3] = {box.p[0], box.p[1], box.p[2]};
  const T scale = h[0] + h[1] + h[2] + L + r;
  const V c = box.to_local(capsule.x);
  const V axis = capsule.axis(0);
  const V u(math::transpose(box.R) * axis);
  const V P0 = c - L * u;
  const V D = (2 * L) * u;  // the core is P0 + t D, t in [0, 1]

  V n;         // box frame, from the box to the capsule
  V q;         // the contact point on the box's surface (box frame)
  T gap;       // along n
  T tc;        // the core parameter of the contact
  int face = -1;  // the box face axis k where n = +-e_k, for the two-point clip

  const T t_near = detail::capsule_box_closest_param(P0, D, h);
  const V P = P0 + t_near * D;
  for (int k = 0; k < 3; ++k) q[k] = detail::clamp_to(P[k], -h[k], h[k]);
  const V out = P - q;
  const T dist = math::norm(out);
  if (dist > T(1e-6) * scale) {
    // Apart: the closest points are exact. A normal within ~2.5 degrees of a
    // face normal counts as that face for the clip.
    n = out * (T(1) / dist);
    gap = dist - r;
    tc = t_near;
    for (int k = 0; k < 3; ++k)
      if (std::fabs(n[k]) > T(0.999)) face = k;
  } else {
    // The core touches or enters the box: the separating axis of least
    // penetration over the three face normals and the three u x e_k, a face
    // preferred unless an edge axis is clearly shallower.
    int kf = 0;
    T sf = T(0);
    for (int k = 0; k < 3; ++k) {
      const T s = std::fabs(c[k]) - h[k] - L * std::fabs(u[k]);
      if (k == 0 || s > sf) {
        sf = s;
        kf = k;
      }
    }
    int ke = -1;
    T se = T(0);
    V ae;
    for (int k = 0; k < 3; ++k) {
      V e;
      e[k] = T(1);
      V ax = u % e;
      const T len = math::norm(ax);
      if (len < T(1e-3)) continue;  // u along e_k: no edge axis
      ax = ax * (T(1) / len);
      const T s = std::fabs(math::dot(c, ax)) -
                  (h[0] * std::fabs(ax[0]) + h[1] * std::fabs(ax[1]) + h[2] * std::fabs(ax[2]));
      if (ke < 0 || s > se) {
        se = s;
        ke = k;
        ae = ax;
      }
    }
    if (ke >= 0 && se > T(0.95) * sf + T(1e-4) * scale) {
      // Edge against the core: n along u x e_k, contact at the closest points
      // of the core and the box edge parallel to e_k on n's side.
      n = math::dot(c, ae) < T(0) ? V(-ae) : ae;
      V e0, e1;
      for (int i = 0; i < 3; ++i) e0[i] = e1[i] = n[i] < T(0) ? -h[i] : h[i];
      e0[ke] = -h[ke];
      e1[ke] = h[ke];
      const V P1 = P0 + D;
      const SegmentClosest<T> cp = segment_segment_closest(P0, P1, e0, e1);
      q = cp.c2;
      tc = cp.s;
      gap = se - r;
    } else {
      // Face kf: n = +-e_kf, the contact at the core's deeper end.
      const T sg = c[kf] < T(0) ? T(-1) : T(1);
      n = V();
      n[kf] = sg;
      tc = sg * u[kf] >= T(0) ? T(0) : T(1);
      const V Pe = P0 + tc * D;
      for (int i = 0; i < 3; ++i) q[i] = detail::clamp_to(Pe[i], -h[i], h[i]);
      q[kf] = sg * h[kf];
      gap = sf - r;
      face = kf;
    }
  }

  const V n_world(box.R * n);
  if (face >= 0 && std::fabs(u[face]) < T(0.1)) {
    // Nearly parallel to face k: clip the core to the face rectangle.
    const int k = face;
    const T sg = n[k] < T(0) ? T(-1) : T(1);
    T lo = T(0), hi = T(1);
    for (int i = 0; i < 3; ++i) {
      if (i == k) continue;
      if (std::fabs(D[i]) <= T(1e-12) * scale) {
        if (std::fabs(P0[i]) > h[i]) hi = T(-1);  // beside the face all along
        continue;
      }
      const T ta = (-h[i] - P0[i]) / D[i], tb = (h[i] - P0[i]) / D[i];
      const T t_min = ta < tb ? ta : tb, t_max = ta < tb ? tb : ta;
      if (t_min > lo) lo = t_min;
      if (t_max < hi) hi = t_max;
    }
    // The contact found above stays in: where the core runs just beside the
    // face's rectangle its closest part is outside the clip. That end keeps
    // the gap found above: along the face normal it would read deeper than
    // the core is, by up to a thousandth of the distance.
    bool kept[2] = {false, false};
    if (hi >= lo) {
      if (tc < lo) lo = tc, kept[0] = true;
      if (tc > hi) hi = tc, kept[1] = true;
    }
    if ((hi - lo) * 2 * L > T(1e-3) * scale) {
      Manifold<T> m;
      V nf;
      nf[k] = sg;
      m.n = V(box.R * nf);
      for (int j = 0; j < 2; ++j) {
        const T t = j == 0 ? lo : hi;
        V Pj = P0 + t * D;
        const T along = sg * Pj[k] - h[k] - r;
        const T g = kept[j] && gap > along ? gap : along;
        for (int i = 0; i < 3; ++i) Pj[i] = detail::clamp_to(Pj[i], -h[i], h[i]);
        Pj[k] = sg * h[k];  // the core point's foot on the face (within its rectangle)
        if (g < margin) m.add(V(box.to_world(Pj) + (g / 2) * m.n), g, std::uint32_t(j));
      }
      return m;
    }
  }
  const std::uint32_t feature = tc <= T(0) ? 0u : (tc >= T(1) ? 1u : 2u);
  return within_margin(one_point<T>(box.to_world(q), n_world, gap, feature), margin);
}

}  // namespace gpusolve::rbd
