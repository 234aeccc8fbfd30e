// Shape kinds as one list, body states, and what the solver asks of a kind
// (bounds, feature size, name) dispatched over that list: each kind's facts
// live in its own header, and a kind without them does not compile.
#pragma once

#include <cstdint>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/box_shape.hpp"
#include "gpusolve/rbd/bodies/capsule_shape.hpp"
#include "gpusolve/rbd/bodies/compound_shape.hpp"
#include "gpusolve/rbd/bodies/plane_shape.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"
#include "gpusolve/rbd/bodies/sphere_shape.hpp"

namespace gpusolve::rbd {

// What a body is doing. Fixed bodies never move (inverse mass and inertia are 0);
// removed bodies keep their slot until the BodyManager rebuilds (thesis 5.1.2).
// A shadow is the copy of a body that another rank owns (rbd/distributed/): it
// moves as an active body does, but meets only active bodies, so that a pair
// of two shadows, or of a shadow and a fixed body, is left to the ranks that own them.
// The moving statuses come first, so that whether a body moves is one
// comparison, as it was before shadows (docs/distributed.md: what it costs).
enum BodyStatus : std::uint8_t { active = 0, shadow = 1, fixed = 2, removed = 3 };

// Whether a body of this status moves (active bodies and shadows).
GPUSOLVE_HD inline bool moves(std::uint8_t status) { return status <= shadow; }

// Every kind, in the order of their values: the one list every dispatch is
// generated from.
template <ShapeKind... K>
struct ShapeKindList {};
using AllShapeKinds = ShapeKindList<sphere, box, plane, capsule, compound>;

namespace detail {
template <ShapeKind... K>
constexpr bool lists_every_kind(ShapeKindList<K...>) {
  int next = 0;
  return ((int(K) == next++) && ...) && next == shape_kinds;
}
}  // namespace detail
static_assert(detail::lists_every_kind(AllShapeKinds{}), "AllShapeKinds lists each ShapeKind once, by value");

// A set of shape kinds, one bit each: which kinds a scene holds, so that
// detection compiles in no more pairs than the scene needs.
using ShapeMask = std::uint32_t;
inline constexpr ShapeMask shape_bit(ShapeKind k) { return ShapeMask(1) << k; }
inline constexpr ShapeMask all_shapes = (ShapeMask(1) << shape_kinds) - 1;
inline constexpr ShapeMask spheres_and_planes = shape_bit(sphere) | shape_bit(plane);

namespace detail {
template <ShapeKind... K>
constexpr ShapeMask part_mask(ShapeKindList<K...>) {
  return ((ShapeTraits<K>::part ? shape_bit(K) : ShapeMask(0)) | ...);
}
}  // namespace detail
// The kinds of the shape-pair table: all but compounds, which are met part by part.
inline constexpr ShapeMask primitives = all_shapes & ~shape_bit(compound);
// The kinds a compound's part can be (ShapeTraits::part).
inline constexpr ShapeMask part_kinds = detail::part_mask(AllShapeKinds{});

namespace detail {
GPUSOLVE_EXEC_CHECK_DISABLE
template <class R, ShapeMask M, class F, class Otherwise, ShapeKind K, ShapeKind... Rest>
GPUSOLVE_HD R visit_kind_in(std::uint8_t kind, F& f, Otherwise& otherwise, ShapeKindList<K, Rest...>) {
  if constexpr ((M & shape_bit(K)) != 0)
    if (kind == K) return f(KindConstant<K>{});
  if constexpr (sizeof...(Rest) > 0)
    return visit_kind_in<R, M>(kind, f, otherwise, ShapeKindList<Rest...>{});
  else
    return otherwise();
}
}  // namespace detail

// f(KindConstant<K>{}) for the kind K of the value `kind` among the kinds of
// M, or otherwise() where it is none of them. Kinds are checked where bodies
// enter (validate_body), so past that only a kind outside M reaches otherwise.
GPUSOLVE_EXEC_CHECK_DISABLE
template <class R, ShapeMask M = all_shapes, class F, class Otherwise>
GPUSOLVE_HD R visit_kind(std::uint8_t kind, F&& f, Otherwise&& otherwise) {
  return detail::visit_kind_in<R, M>(kind, f, otherwise, AllShapeKinds{});
}

// A kind's name, for messages ("unknown" for a value that names none).
inline const char* shape_name(std::uint8_t kind) {
  return visit_kind<const char*>(
      kind, [](auto k) { return ShapeTraits<decltype(k)::value>::name; }, [] { return "unknown"; });
}

// Whether a compound may hold a part of this kind.
GPUSOLVE_HD constexpr bool part_kind(std::uint8_t k) { return k < shape_kinds && (part_kinds & (ShapeMask(1) << k)) != 0; }

// The radius of the smallest sphere about a shape's centre that holds it, from
// its parameters (+infinity for a plane, which bounds nothing).
template <class T>
GPUSOLVE_HD T shape_bound(std::uint8_t kind, T p0, T p1, T p2) {
  return visit_kind<T>(
      kind, [&](auto k) { return ShapeTraits<decltype(k)::value>::bound(p0, p1, p2); },
      [] { return std::numeric_limits<T>::infinity(); });
}

// The size penetration is measured against (statistics/accuracy.hpp): a
// sphere's or capsule's radius, a box's smallest half extent, a compound's
// smallest part's; a plane has none (+infinity), so a body on a plane is
// measured against the body.
template <class T>
GPUSOLVE_HD T shape_feature_size(std::uint8_t kind, T p0, T p1, T p2) {
  return visit_kind<T>(
      kind, [&](auto k) { return ShapeTraits<decltype(k)::value>::feature(p0, p1, p2); },
      [] { return std::numeric_limits<T>::infinity(); });
}

}  // namespace gpusolve::rbd
