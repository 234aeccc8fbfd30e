// The manifolds of two bodies: one from the shape-pair table for two
// primitives; where a body is a compound, those of its pairs of parts that
// touch, each part placed in the world and met through its own kind's pairs,
// merged by normal.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/merged_manifolds.hpp"
#include "gpusolve/rbd/collision/narrow_phase.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// The feature id of a point between part pa of body a and part pb of body b:
// the pair's own id (below 2^16) with the parts in the top bytes, so that warm
// starting tells the points of different part pairs apart.
GPUSOLVE_HD inline std::uint32_t part_feature(std::uint32_t feature, std::uint32_t pa, std::uint32_t pb) {
  return feature | (pa << 24) | (pb << 16);
}

namespace detail {

// A body's primitives: a compound's parts, any other body itself.
template <class View>
GPUSOLVE_HD std::uint32_t part_count(const View& b, std::size_t i) {
  return b.shape[i] == compound ? std::uint32_t(b.shape_param(i, 0)) : 1u;
}

// Primitive k of body i in the world and its kind: part k of a compound at
// x_i + R_i p_k, turned by R_i R_k; any other body itself (placed_shape).
template <class T, class View>
GPUSOLVE_HD PlacedShape<T> placed_primitive(const View& b, std::size_t i, std::uint32_t k, std::uint8_t& kind) {
  kind = b.shape[i];
  if (kind != compound) return placed_shape<T>(b, i);
  const std::size_t part = b.first_part[i] + k;
  const auto& parts = b.parts;
  kind = parts.shape[part];
  const math::Matrix3x3<T> R(b.R(i, 0), b.R(i, 1), b.R(i, 2), b.R(i, 3), b.R(i, 4), b.R(i, 5), b.R(i, 6),
                             b.R(i, 7), b.R(i, 8));
  const math::Matrix3x3<T> Rk(parts.R(part, 0), parts.R(part, 1), parts.R(part, 2), parts.R(part, 3),
                              parts.R(part, 4), parts.R(part, 5), parts.R(part, 6), parts.R(part, 7),
                              parts.R(part, 8));
  const math::Vector3<T> offset(parts.pos(part, 0), parts.pos(part, 1), parts.pos(part, 2));
  PlacedShape<T> s{math::Vector3<T>(math::load3<T>(b.pos, i) + R * offset), math::Matrix3x3<T>(R * Rk), {}};
  for (std::size_t c = 0; c < shape_param_rows; ++c) s.p[c] = parts.shape_param(part, c);
  return s;
}

// Whether a placed primitive's bounding sphere comes within the margin of
// body j's (Bodies::radius; a plane's is infinite).
template <class T, class View>
GPUSOLVE_HD bool reaches_body(std::uint8_t ka, const PlacedShape<T>& a, const View& b, std::size_t j, T margin) {
  const T reach = shape_bound<T>(ka, a.p[0], a.p[1], a.p[2]) + b.radius[j] + margin;
  const math::Vector3<T> d(a.x - math::load3<T>(b.pos, j));
  return !(math::dot(d, d) >= reach * reach);
}

// Whether two placed primitives' bounding spheres come within the margin.
template <class T>
GPUSOLVE_HD bool bounds_meet(std::uint8_t ka, const PlacedShape<T>& a, std::uint8_t kb, const PlacedShape<T>& b,
                             T margin) {
  const T reach = shape_bound<T>(ka, a.p[0], a.p[1], a.p[2]) + shape_bound<T>(kb, b.p[0], b.p[1], b.p[2]) +
                  margin;
  const math::Vector3<T> d(a.x - b.x);
  return !(math::dot(d, d) >= reach * reach);  // a plane's infinite reach always meets
}

}  // namespace detail

// Calls f(manifold) for each manifold of body i (a) against body j (b) that
// has points below the margin, over the kinds of the mask M: one for two
// primitives; where a body is a compound, the part pairs' manifolds (a's
// parts that reach body j, b's parts whose bounds meet them) merged by normal
// (MergedManifolds).
template <ShapeMask M, class T, class View, class F>
GPUSOLVE_HD void for_each_manifold(const View& b, std::size_t i, std::size_t j, T margin, F&& f) {
  if constexpr ((M & shape_bit(compound)) != 0) {
    if (b.shape[i] == compound || b.shape[j] == compound) {
      const std::uint32_t na = detail::part_count(b, i), nb = detail::part_count(b, j);
      MergedManifolds<T> merged;
      for (std::uint32_t pa = 0; pa < na; ++pa) {
        std::uint8_t ka;
        const PlacedShape<T> A = detail::placed_primitive<T>(b, i, pa, ka);
        if (na > 1 && !detail::reaches_body(ka, A, b, j, margin)) continue;  // a part far from body j
        for (std::uint32_t pb = 0; pb < nb; ++pb) {
          std::uint8_t kb;
          const PlacedShape<T> B = detail::placed_primitive<T>(b, j, pb, kb);
          if (na * nb > 1 && !detail::bounds_meet(ka, A, kb, B, margin)) continue;
          Manifold<T> m = collide<M & primitives, T>(ka, A, kb, B, margin);
          if (m.count == 0) continue;
          for (int k = 0; k < m.count; ++k) m.points[k].feature = part_feature(m.points[k].feature, pa, pb);
          if (!merged.merge(m)) f(m);
        }
      }
      merged.for_each(f);
      return;
    }
  }
  const Manifold<T> m =
      collide<M & primitives, T>(b.shape[i], placed_shape<T>(b, i), b.shape[j], placed_shape<T>(b, j), margin);
  if (m.count > 0) f(m);
}

}  // namespace gpusolve::rbd
