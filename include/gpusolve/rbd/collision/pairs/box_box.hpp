// Box against box: the separating axis test, then a clipped face or an edge pair.
#pragma once

#include <cmath>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/reduce_points.hpp"
#include "gpusolve/rbd/collision/pairs/segment.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// Feature ids of box_box:
//   face contact: bits 0-2 and 3-5 the two polygon edges meeting at the point, in
//     the incident face's winding (0-3: incident face edge k, from corner k to
//     k+1; 4-7: reference side 4 + s); two incident edges make an incident
//     vertex, two sides a reference corner, one of each a crossing. Bits 6-8 the
//     incident face, 9-11 the reference face (2 axis + 1 on the + side), bit 12
//     set when the reference face is b's, bit 13 clear.
//   edge contact: bit 13 set, bits 0-3 a's edge, 4-7 b's edge, each 4 axis +
//     2 (+ side of axis+1) + (+ side of axis+2).
//   closest points of boxes apart past an edge or corner: bit 14 alone.
namespace detail {

// A vertex of the clipped polygon and the tags of its incoming and outgoing edges.
template <class T>
struct ClipPoint {
  math::Vector3<T> p;
  std::uint32_t in, out;
};

// The half extent of box b along the world direction L (not necessarily unit).
template <class T>
GPUSOLVE_HD T box_radius(const PlacedShape<T>& b, const math::Vector3<T>& L) {
  T r = 0;
  for (int k = 0; k < 3; ++k) r += b.p[k] * std::fabs(math::dot(b.axis(k), L));
  return r;
}

// Face contact: the face of r on its axis i facing o is the reference; o's face
// most anti-parallel to it is clipped to the reference's sides (Sutherland-Hodgman).
template <class T>
GPUSOLVE_HD Manifold<T> box_face_contact(const PlacedShape<T>& r, const PlacedShape<T>& o, int i, bool ref_b,
                                         T margin) {
  const math::Vector3<T> ri = r.axis(i);
  const bool rpos = math::dot(math::Vector3<T>(o.x - r.x), ri) >= T(0);
  const math::Vector3<T> nr = rpos ? ri : math::Vector3<T>(-ri);  // reference normal, r towards o
  int j = 0;
  T dj = math::dot(o.axis(0), nr);
  for (int k = 1; k < 3; ++k) {
    const T dk = math::dot(o.axis(k), nr);
    if (std::fabs(dk) > std::fabs(dj)) j = k, dj = dk;
  }
  const bool ipos = dj < T(0);  // the incident face's outward normal opposes nr
  const int u = (j + 1) % 3, v = (j + 2) % 3;
  const math::Vector3<T> fc = o.x + (ipos ? o.p[j] : -o.p[j]) * o.axis(j);
  const math::Vector3<T> eu = o.p[u] * o.axis(u), ev = o.p[v] * o.axis(v);
  ClipPoint<T> polys[2][8];  // the polygon and the next one, taking turns (no copy between sides)
  ClipPoint<T>* poly = polys[0];
  ClipPoint<T>* next = polys[1];
  int n = 4;
  for (std::uint32_t k = 0; k < 4; ++k) {  // corners (+,+), (-,+), (-,-), (+,-) in (u, v)
    const T su = (k == 0 || k == 3) ? T(1) : T(-1), sv = k < 2 ? T(1) : T(-1);
    poly[k] = {math::Vector3<T>(fc + su * eu + sv * ev), (k + 3) % 4, k};
  }
  for (std::uint32_t s = 0; s < 4 && n > 0; ++s) {  // sides (+w, -w) for w = i+1, then i+2
    const int w = (i + 1 + int(s / 2)) % 3;
    const math::Vector3<T> sn = s % 2 ? math::Vector3<T>(-r.axis(w)) : r.axis(w);
    const T off = math::dot(sn, r.x) + r.p[w];
    // A corner within a ten-thousandth of the box of the side (boxes of one
    // width stacked) stands for the crossings beside it where a neighbour lies
    // inside: as rounding goes it would be a corner one step and two crossings
    // the next, and its feature id with it. Without a neighbour inside, a
    // corner just outside goes (the faces only touch beyond the side).
    const T on = T(1e-4) * r.p[w];
    T d[8];
    for (int k = 0; k < n; ++k) d[k] = math::dot(sn, poly[k].p) - off;
    int m = 0;
    for (int k = 0; k < n; ++k) {
      const T dp = d[k], dq = d[(k + 1) % n], dr = d[(k + n - 1) % n];
      const bool keep = dp <= T(0) || (dp <= on && (dq < -on || dr < -on));
      if (keep && m < 8) next[m++] = poly[k];
      if (((dp < -on && dq > on) || (dp > on && dq < -on)) && m < 8) {
        const ClipPoint<T>& P = poly[k];
        const math::Vector3<T> x = P.p + (dp / (dp - dq)) * (poly[(k + 1) % n].p - P.p);
        next[m++] = dp < T(0) ? ClipPoint<T>{x, P.out, 4 + s} : ClipPoint<T>{x, 4 + s, P.out};
      }
    }
    n = m;
    ClipPoint<T>* const done = poly;
    poly = next, next = done;
  }
  const std::uint32_t base = (std::uint32_t(ref_b) << 12) | (std::uint32_t(2 * i + rpos) << 9) |
                             (std::uint32_t(2 * j + ipos) << 6);
  const T ref_off = math::dot(nr, r.x) + r.p[i];
  ManifoldPoint<T> c[8];
  int count = 0;
  for (int k = 0; k < n; ++k) {
    const T gap = math::dot(nr, poly[k].p) - ref_off;
    if (gap < margin)
      c[count++] = {math::Vector3<T>(poly[k].p - (gap / 2) * nr), gap, base | poly[k].in | (poly[k].out << 3)};
  }
  return reduce_to_four(c, count, ref_b ? nr : math::Vector3<T>(-nr));
}

// The edge of box b along axis e nearest the direction L (its + side where
// dot(axis, L) > 0): its centre in the world, and its id (4 e + 2 s1 + s2).
template <class T>
GPUSOLVE_HD math::Vector3<T> box_support_edge(const PlacedShape<T>& b, int e, const math::Vector3<T>& L,
                                              std::uint32_t& id) {
  math::Vector3<T> l;
  id = 4u * std::uint32_t(e);
  for (int t = 1; t <= 2; ++t) {
    const int k = (e + t) % 3;
    const bool pos = math::dot(b.axis(k), L) > T(0);
    l[k] = pos ? b.p[k] : -b.p[k];
    id |= std::uint32_t(pos) << (2 - t);
  }
  return b.to_world(l);
}

// Edge contact on the axis a.axis(i) x b.axis(j): one point midway between the
// closest points of a's and b's edges along those axes nearest each other.
// False when those points fall off the edges (by more than slop): no edge crossing.
template <class T>
GPUSOLVE_HD bool box_edge_contact(const PlacedShape<T>& a, const PlacedShape<T>& b, int i, int j, T margin,
                                  T slop, Manifold<T>& out) {
  const math::Vector3<T> da = a.axis(i), db = b.axis(j);
  math::Vector3<T> n = da % db;
  n = math::Vector3<T>((T(1) / math::norm(n)) * n);
  if (math::dot(math::Vector3<T>(a.x - b.x), n) < T(0)) n = math::Vector3<T>(-n);
  std::uint32_t ea, eb;
  const math::Vector3<T> pa = box_support_edge(a, i, math::Vector3<T>(-n), ea);
  const math::Vector3<T> pb = box_support_edge(b, j, n, eb);
  // Closest points of the lines pa + s da and pb + t db, clamped to the edges.
  const math::Vector3<T> w = pa - pb;
  const T c = math::dot(da, db), d = math::dot(da, w), e = math::dot(db, w);
  const T denom = T(1) - c * c;
  T s = (c * e - d) / denom, t = (e - c * d) / denom;
  if (std::fabs(s) > a.p[i] + slop || std::fabs(t) > b.p[j] + slop) return false;
  s = std::fmax(-a.p[i], std::fmin(a.p[i], s));
  t = std::fmax(-b.p[j], std::fmin(b.p[j], t));
  const math::Vector3<T> ca = pa + s * da, cb = pb + t * db;
  const T gap = math::dot(math::Vector3<T>(ca - cb), n);
  out = within_margin(one_point<T>(cb, n, gap, (1u << 13) | ea | (eb << 4)), margin);
  return true;
}

// Whether the edge axis L (length len) lies within 5 degrees of a face normal
// of a or b: two edges lying flat on a face, as where a box comes down nearly
// flat across the seam of two others. Their one crossing point would leave the
// rest of the face free to sink in within the step (a cube tumbling onto such a
// seam went 1.7% of its half extent into a box).
template <class T>
GPUSOLVE_HD bool along_a_face(const PlacedShape<T>& a, const PlacedShape<T>& b, const math::Vector3<T>& L, T len) {
  const T cos_5_degrees = T(0.9962);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(math::dot(a.axis(k), L)) > cos_5_degrees * len ||
        std::fabs(math::dot(b.axis(k), L)) > cos_5_degrees * len)
      return true;
  return false;
}

// Axis k of the separating axis test, not normalised: a's face normals (0-2),
// b's (3-5), the crossings of a's edge (k - 6) / 3 with b's edge (k - 6) % 3.
template <class T>
GPUSOLVE_HD math::Vector3<T> sat_axis(const PlacedShape<T>& a, const PlacedShape<T>& b, int k) {
  if (k >= 6) return a.axis((k - 6) / 3) % b.axis((k - 6) % 3);
  return k < 3 ? a.axis(k) : b.axis(k % 3);
}

// The point of box b closest to the world point w (w itself inside b).
template <class T>
GPUSOLVE_HD math::Vector3<T> closest_in_box(const PlacedShape<T>& b, const math::Vector3<T>& w) {
  math::Vector3<T> l = b.to_local(w);
  for (int k = 0; k < 3; ++k) l[k] = clamp_to(l[k], -b.p[k], b.p[k]);
  return b.to_world(l);
}

// Boxes apart whose least separating axis leaves nothing to clip: one box
// beside and above another's edge or corner, no face over a face. One point
// on the line of their closest points, found by alternating projections (each
// a clamp in one box's frame; they converge to the closest pair of two convex
// sets, slowly where faces are nearly parallel), its gap their separation
// along that line. Where that line does not yet separate them as well as the
// best of the 15 axes (sat_axis `axis`, separating them by s > 0), the point
// takes that axis and s instead: the gap is positive and never exceeds their distance.
// Without it such a pair had no contact, and a cube thrown at a box's edge
// went up to 1.7% of its half extent into it within a step.
template <class T>
GPUSOLVE_HD_NOINLINE Manifold<T> box_closest_contact(const PlacedShape<T>& a, const PlacedShape<T>& b, int axis, T s,
                                                     T margin) {
  math::Vector3<T> L = sat_axis(a, b, axis);
  L = math::Vector3<T>((T(1) / math::norm(L)) * L);
  math::Vector3<T> pb = closest_in_box(b, a.x), pa = closest_in_box(a, pb);
  GPUSOLVE_NO_UNROLL
  for (int k = 0; k < 8; ++k) pb = closest_in_box(b, pa), pa = closest_in_box(a, pb);
  const math::Vector3<T> d = pa - pb;
  const T len = math::norm(d);
  if (len > T(0)) {
    const math::Vector3<T> n = (T(1) / len) * d;
    const T gap = math::dot(math::Vector3<T>(a.x - b.x), n) - box_radius(a, n) - box_radius(b, n);
    if (gap > s) L = n, s = gap;
  }
  if (math::dot(math::Vector3<T>(a.x - b.x), L) < T(0)) L = math::Vector3<T>(-L);  // from b towards a
  return within_margin(one_point<T>(pb, L, s, 1u << 14), margin);
}

// The smallest gap among a manifold's points.
template <class T>
GPUSOLVE_HD T deepest_gap(const Manifold<T>& m) {
  T g = m.points[0].gap;
  for (int k = 1; k < m.count; ++k) g = std::fmin(g, m.points[k].gap);
  return g;
}

}  // namespace detail

// Box a against box b (half extents p[0..2]): the axis of least overlap among
// the 6 face normals and 9 edge crossings, no points when one separates by the
// margin or more. Face axes win over edge axes unless those are clearly better
// (5% and a fifth of the slop), and a's faces over b's (2%), so near ties pick
// the same contact every step; an edge axis whose edges do not cross falls back
// to the best face. An edge axis along a face (along_a_face) while the boxes
// are still apart along it, a landing, gives way to the face where the face's
// points are no deeper than the edges' separation; boxes already pressed
// together keep the edge axis (the face's points pushed them out by far:
// docs/shapes.md). Boxes apart with no face over a face (past an edge or a
// corner) get one point at their closest points.
template <class T>
GPUSOLVE_HD Manifold<T> box_box(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) {
  const math::Vector3<T> d = a.x - b.x;
  T hmin = a.p[0];
  for (int k = 0; k < 3; ++k) hmin = std::fmin(hmin, std::fmin(a.p[k], b.p[k]));
  const T slop = T(0.01) * hmin;                           // absolute part of the preference
  const T parallel = sizeof(T) == 4 ? T(1e-3) : T(1e-6);  // |cross| below: edges parallel, skip
  int best[3] = {-1, -1, -1};  // the least separating axis among a's faces, b's faces, the edges
  T best_s[3] = {0, 0, 0};
  for (int k = 0; k < 15; ++k) {
    const math::Vector3<T> L = detail::sat_axis(a, b, k);
    const T len = math::norm(L);
    if (k >= 6 && len < parallel) continue;
    const T s = (std::fabs(math::dot(d, L)) - detail::box_radius(a, L) - detail::box_radius(b, L)) / len;
    if (s >= margin) return {};
    const int g = k < 3 ? 0 : (k < 6 ? 1 : 2);
    if (best[g] < 0 || s > best_s[g]) best[g] = k, best_s[g] = s;
  }
  const auto clearly = [&](int g, int than, T rel) {
    return best[g] >= 0 && best_s[g] > best_s[than] + rel * (std::fabs(best_s[than]) + slop);
  };
  const int face = clearly(1, 0, T(0.02)) ? 1 : 0;
  // An edge beats the face by 5% of the overlap and a fifth of the slop: near
  // touching, a face's points hold a box tipping off an edge (docs/shapes.md).
  const bool edge_wins = best[2] >= 0 && best_s[2] > best_s[face] + T(0.05) * std::fabs(best_s[face]) + T(0.2) * slop;
  const int i = edge_wins ? (best[2] - 6) / 3 : 0, j = edge_wins ? (best[2] - 6) % 3 : 0;
  const math::Vector3<T> L = a.axis(i) % b.axis(j);
  const bool landing = edge_wins && best_s[2] > T(0) && detail::along_a_face(a, b, L, math::norm(L));
  Manifold<T> m;
  if (edge_wins && !landing && detail::box_edge_contact(a, b, i, j, margin, slop, m)) return m;
  const Manifold<T> f = face == 0 ? detail::box_face_contact(a, b, best[0], false, margin)
                                  : detail::box_face_contact(b, a, best[1] - 3, true, margin);
  const bool face_holds = f.count > 0 && detail::deepest_gap(f) >= best_s[2] - slop;
  if (landing && !face_holds && detail::box_edge_contact(a, b, i, j, margin, slop, m)) return m;
  if (f.count > 0) return f;
  const int g = best_s[0] >= best_s[1] ? (best_s[0] >= best_s[2] ? 0 : 2) : (best_s[1] >= best_s[2] ? 1 : 2);
  return best_s[g] > T(0) ? detail::box_closest_contact(a, b, best[g], best_s[g], margin) : f;  // apart: an axis separates them
}

}  // namespace gpusolve::rbd
