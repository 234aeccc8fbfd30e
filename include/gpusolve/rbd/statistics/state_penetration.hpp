// Penetration judged from the bodies' states alone: positions, orientations
// and shapes, not the contacts a detection found. The same figure a peer
// engine's states give (docs/piles.md measures NVIDIA Newton so), and a check on our
// own detection: a pair it missed still counts here. Host side, in double.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "gpusolve/math.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"
#include "gpusolve/rbd/collision/pairs/segment.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// The deepest overlap among the bodies, relative to the smaller feature size
// of the pair (feature_size: a radius, a box's smallest half extent, a
// compound's smallest part's), and the pair that has it (none: a = b = 0).
struct StatePenetration {
  double relative = 0;
  std::size_t a = 0, b = 0;
};

namespace detail {

using V3 = math::Vector3<double>;

// One primitive of a body in the world: a body itself, or a compound's part.
struct StatePrimitive {
  ShapeKind kind;
  PlacedShape<double> s;
  double bound;    // bounding-sphere radius (planes: infinite)
  double feature;  // the body's feature size
  std::size_t body;
  bool moving;
};

// The overlap depth of two boxes: the least overlap of their projections over
// the 15 separating axes (3 + 3 face normals, 9 edge crossings); 0 where an
// axis separates them.
inline double box_box_depth(const PlacedShape<double>& a, const PlacedShape<double>& b) {
  const V3 d(b.x - a.x);
  double depth = std::numeric_limits<double>::infinity();
  const auto on_axis = [&](V3 axis) {
    const double len = math::norm(axis);
    if (len < 1e-9) return true;  // parallel edges: their crossing is no axis
    axis = axis * (1 / len);
    double ra = 0, rb = 0;
    for (int k = 0; k < 3; ++k) {
      ra += a.p[k] * std::fabs(math::dot(a.axis(k), axis));
      rb += b.p[k] * std::fabs(math::dot(b.axis(k), axis));
    }
    const double overlap = ra + rb - std::fabs(math::dot(d, axis));
    depth = std::min(depth, overlap);
    return overlap > 0;
  };
  for (int k = 0; k < 3; ++k)
    if (!on_axis(a.axis(k)) || !on_axis(b.axis(k))) return 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!on_axis(V3(a.axis(i) % b.axis(j)))) return 0;
  return depth;
}

// A ball of radius r at c against a box: r less the signed distance from c
// to the box (outside, the distance; inside, less its distance to the nearest
// face). Negative while apart: concave along a line, as the signed distance to
// a convex body is convex.
inline double ball_box_signed_depth(const V3& c, double r, const PlacedShape<double>& box) {
  const V3 local = box.to_local(c);
  double outside2 = 0, inside = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double excess = std::fabs(local[k]) - box.p[k];
    if (excess > 0) outside2 += excess * excess;
    inside = std::min(inside, -excess);
  }
  return outside2 > 0 ? r - std::sqrt(outside2) : r + inside;
}
inline double ball_box_depth(const V3& c, double r, const PlacedShape<double>& box) {
  return std::max(0.0, ball_box_signed_depth(c, r, box));
}

// A capsule's segment ends.
inline std::array<V3, 2> capsule_ends(const PlacedShape<double>& c) {
  const V3 half(c.axis(0) * c.p[1]);
  return {V3(c.x - half), V3(c.x + half)};
}

// How far the deepest point of a primitive lies past the plane (n, d), whose
// solid side is n.x < d.
inline double plane_depth(const PlacedShape<double>& plane, ShapeKind kind, const PlacedShape<double>& s) {
  const V3 n(plane.p[0], plane.p[1], plane.p[2]);
  const double d = plane.p[3];
  double lowest = math::dot(n, s.x) - d;  // the centre's height above the plane
  if (kind == sphere) lowest -= s.p[0];
  if (kind == box)
    for (int k = 0; k < 3; ++k) lowest -= s.p[k] * std::fabs(math::dot(n, s.axis(k)));
  if (kind == capsule) lowest -= s.p[1] * std::fabs(math::dot(n, s.axis(0))) + s.p[0];
  return std::max(0.0, -lowest);
}

// The overlap depth of two primitives (neither a compound). A capsule against
// a box: r less the signed distance from the box to the capsule's segment at
// its least; that distance is convex along the segment (the signed distance
// of a convex body is a convex function), so a ternary search finds it.
inline double primitive_depth(ShapeKind ka, const PlacedShape<double>& a, ShapeKind kb, const PlacedShape<double>& b) {
  if (ka > kb) return primitive_depth(kb, b, ka, a);  // sphere < box < plane < capsule
  if (ka == plane && kb == plane) return 0;
  if (ka == plane) return plane_depth(a, kb, b);
  if (kb == plane) return plane_depth(b, ka, a);
  if (ka == sphere && kb == sphere) return std::max(0.0, a.p[0] + b.p[0] - math::norm(V3(a.x - b.x)));
  if (ka == sphere && kb == box) return ball_box_depth(a.x, a.p[0], b);
  if (ka == box && kb == box) return box_box_depth(a, b);
  const auto ends = capsule_ends(b);  // kb == capsule from here on
  if (ka == sphere)
    return std::max(0.0, a.p[0] + b.p[0] - math::norm(V3(a.x - segment_closest_point(ends[0], ends[1], a.x))));
  if (ka == capsule) {
    const auto e = capsule_ends(a);
    const auto c = segment_segment_closest(e[0], e[1], ends[0], ends[1]);
    return std::max(0.0, a.p[0] + b.p[0] - std::sqrt(c.dist2));
  }
  // ka == box. Signed, not clamped at zero: on a clamped depth a short stretch
  // of overlap between the search's probes read zero and was cut away.
  const auto depth_at = [&](double t) {
    return ball_box_signed_depth(V3(ends[0] + (ends[1] - ends[0]) * t), b.p[0], a);
  };
  double lo = 0, hi = 1;
  for (int k = 0; k < 80; ++k) {  // (2/3)^80: below 1e-14 of the segment
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (depth_at(m1) < depth_at(m2))
      lo = m1;
    else
      hi = m2;
  }
  return std::max({0.0, depth_at(0), depth_at(1), depth_at((lo + hi) / 2)});
}

template <class T>
PlacedShape<double> placed(const std::array<T, 3>& pos, const math::Matrix3x3<double>& R,
                           const std::array<T, shape_param_rows>& p) {
  PlacedShape<double> s{V3(pos[0], pos[1], pos[2]), R, {}};
  for (std::size_t c = 0; c < shape_param_rows; ++c) s.p[c] = double(p[c]);
  return s;
}

// Body i's primitives, appended to `out`.
template <class T>
void add_state_primitives(const BodySet<T>& set, std::size_t i, std::vector<StatePrimitive>& out) {
  const Body<T>& b = set[i];
  if (b.status == removed) return;
  const auto R = math::to_rotation_matrix(math::Quaternion<double>(b.q[0], b.q[1], b.q[2], b.q[3]));
  const bool moving = moves(b.status);
  if (b.shape != compound) {
    const PlacedShape<double> s = placed(b.pos, R, b.shape_param);
    const double bound = shape_bound<double>(b.shape, s.p[0], s.p[1], s.p[2]);
    out.push_back({b.shape, s, bound, shape_feature_size<double>(b.shape, s.p[0], s.p[1], s.p[2]), i, moving});
    return;
  }
  const std::size_t first = out.size(), parts = std::size_t(b.shape_param[0]);
  double feature = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < parts; ++k) {
    const Part<T>& part = set.parts()[b.first_part + k];
    const V3 offset(part.pos[0], part.pos[1], part.pos[2]);
    const V3 x(R * offset);
    const auto Rk = math::to_rotation_matrix(math::Quaternion<double>(part.q[0], part.q[1], part.q[2], part.q[3]));
    PlacedShape<double> s = placed(b.pos, math::Matrix3x3<double>(R * Rk), part.shape_param);
    s.x = V3(s.x + x);
    feature = std::min(feature, shape_feature_size<double>(part.shape, s.p[0], s.p[1], s.p[2]));
    out.push_back({part.shape, s, shape_bound<double>(part.shape, s.p[0], s.p[1], s.p[2]), 0, i, moving});
  }
  for (std::size_t k = first; k < out.size(); ++k) out[k].feature = feature;
}

}  // namespace detail

// Calls f(a, b, relative) for each pair of bodies of `set` (a < b, at least one
// of them moving; parts of one compound are not compared) whose primitives
// overlap, from their states alone: relative is the overlap over the smaller
// feature size, once per overlapping primitive pair. Candidate pairs come from
// a grid of the primitives' bounding spheres, whose cell is the largest moving
// primitive's diameter; planes and larger fixed primitives are tested against
// every primitive.
template <class T, class F>
void for_each_state_overlap(const BodySet<T>& set, F&& f) {
  std::vector<detail::StatePrimitive> prims;
  for (std::size_t i = 0; i < set.size(); ++i) detail::add_state_primitives(set, i, prims);
  double cell = 0;
  for (const auto& p : prims)
    if (p.moving && p.kind != plane) cell = std::max(cell, 2 * p.bound);
  if (!(cell > 0)) cell = 1;
  const auto meet = [&](const detail::StatePrimitive& a, const detail::StatePrimitive& b) {
    if (a.body == b.body || (!a.moving && !b.moving)) return;
    if (a.kind != plane && b.kind != plane && math::norm(detail::V3(a.s.x - b.s.x)) >= a.bound + b.bound) return;
    const double depth = detail::primitive_depth(a.kind, a.s, b.kind, b.s);
    if (depth > 0) f(std::min(a.body, b.body), std::max(a.body, b.body), depth / std::min(a.feature, b.feature));
  };
  // Planes and fixed primitives larger than a cell meet every primitive; the rest a grid.
  std::vector<bool> wide(prims.size());
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  const auto key = [](long x, long y, long z) {
    return (std::uint64_t(x & 0x1fffff) << 42) | (std::uint64_t(y & 0x1fffff) << 21) | std::uint64_t(z & 0x1fffff);
  };
  const auto cell_of = [cell](double v) { return long(std::floor(v / cell)); };
  for (std::size_t k = 0; k < prims.size(); ++k) {
    const auto& p = prims[k];
    wide[k] = p.kind == plane || 2 * p.bound > cell;
    if (!wide[k]) grid[key(cell_of(p.s.x[0]), cell_of(p.s.x[1]), cell_of(p.s.x[2]))].push_back(k);
  }
  for (std::size_t w = 0; w < prims.size(); ++w)
    if (wide[w])
      for (std::size_t k = 0; k < prims.size(); ++k)
        if (!wide[k] || k > w) meet(prims[w], prims[k]);
  for (std::size_t k = 0; k < prims.size(); ++k) {
    const auto& p = prims[k];
    if (wide[k]) continue;
    const long cx = cell_of(p.s.x[0]), cy = cell_of(p.s.x[1]), cz = cell_of(p.s.x[2]);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second)
            if (j > k) meet(p, prims[j]);
        }
  }
}

// The deepest overlap of any two bodies of `set` for which counts(i) holds of
// both (for_each_state_overlap's pairs).
template <class T, class Counts>
StatePenetration state_penetration(const BodySet<T>& set, Counts counts) {
  StatePenetration worst;
  for_each_state_overlap(set, [&](std::size_t a, std::size_t b, double relative) {
    if (relative > worst.relative && counts(a) && counts(b)) worst = {relative, a, b};
  });
  return worst;
}

// The deepest overlap of any two bodies of `set`, every pair counted.
template <class T>
StatePenetration state_penetration(const BodySet<T>& set) {
  return state_penetration(set, [](std::size_t) { return true; });
}

}  // namespace gpusolve::rbd
