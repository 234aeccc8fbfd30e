// Narrow phase: the shape-pair table. One function per pair of shape kinds,
// each in its own header under pairs/, registered here once (as Box2D v3's
// contact table and Jolt's CollisionDispatch do); the reversed pair is the
// same function with the bodies swapped and the normal turned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/box_box.hpp"
#include "gpusolve/rbd/collision/pairs/box_plane.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_box.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_capsule.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_plane.hpp"
#include "gpusolve/rbd/collision/pairs/sphere_box.hpp"
#include "gpusolve/rbd/collision/pairs/sphere_capsule.hpp"
#include "gpusolve/rbd/collision/pairs/sphere_plane.hpp"
#include "gpusolve/rbd/collision/pairs/sphere_sphere.hpp"
#include "gpusolve/rbd/collision/placed_shape.hpp"

namespace gpusolve::rbd {

// The table: ShapePair<A, B>::collide(a, b, margin) for kinds A <= B, the
// manifold of a (kind A) against b (kind B), points whose gap is below the
// margin. A pair without an entry is an incomplete type: using it does not compile.
template <ShapeKind A, ShapeKind B>
struct ShapePair;

#define GPUSOLVE_SHAPE_PAIR(A, B, call)                                                                   \
  template <>                                                                                            \
  struct ShapePair<A, B> {                                                                               \
    template <class T>                                                                                   \
    GPUSOLVE_HD static Manifold<T> collide(const PlacedShape<T>& a, const PlacedShape<T>& b, T margin) { \
      return call;                                                                                       \
    }                                                                                                    \
  };
GPUSOLVE_SHAPE_PAIR(sphere, sphere, sphere_sphere(a, b, margin))
GPUSOLVE_SHAPE_PAIR(sphere, box, sphere_box(a, b, margin))
GPUSOLVE_SHAPE_PAIR(sphere, plane, sphere_plane(a, b, margin))
GPUSOLVE_SHAPE_PAIR(sphere, capsule, sphere_capsule(a, b, margin))
GPUSOLVE_SHAPE_PAIR(box, box, box_box(a, b, margin))
GPUSOLVE_SHAPE_PAIR(box, plane, box_plane(a, b, margin))
GPUSOLVE_SHAPE_PAIR(box, capsule, capsule_box(b, a, margin).flipped())
GPUSOLVE_SHAPE_PAIR(plane, plane, ((void)a, (void)b, (void)margin, Manifold<T>{}))  // planes are fixed: they never meet
GPUSOLVE_SHAPE_PAIR(plane, capsule, capsule_plane(b, a, margin).flipped())
GPUSOLVE_SHAPE_PAIR(capsule, capsule, capsule_capsule(a, b, margin))
#undef GPUSOLVE_SHAPE_PAIR

namespace detail {

// Body a of kind A against body b of the runtime kind kb, over the kinds of
// the mask M only (the others are never compiled in).
template <ShapeMask M, ShapeKind A, class T>
GPUSOLVE_HD Manifold<T> collide_with(const PlacedShape<T>& a, std::uint8_t kb, const PlacedShape<T>& b, T margin) {
  const auto pair = [&](auto kind) -> Manifold<T> {
    constexpr ShapeKind B = decltype(kind)::value;
    if constexpr ((M & shape_bit(B)) == 0)
      return {};
    else if constexpr (A <= B)
      return ShapePair<A, B>::collide(a, b, margin);
    else
      return ShapePair<B, A>::collide(b, a, margin).flipped();
  };
  switch (kb) {
    case sphere: return pair(std::integral_constant<ShapeKind, sphere>{});
    case box: return pair(std::integral_constant<ShapeKind, box>{});
    case plane: return pair(std::integral_constant<ShapeKind, plane>{});
    case capsule: return pair(std::integral_constant<ShapeKind, capsule>{});
    default: return {};
  }
}

}  // namespace detail

// The manifold of body a (kind ka) against body b (kind kb), with the kinds a
// scene holds in M; a kind outside M gives no points. Not inlined on the
// device: the contact count and the contact write share one copy per M.
template <ShapeMask M = all_shapes, class T>
GPUSOLVE_HD_NOINLINE Manifold<T> collide(std::uint8_t ka, const PlacedShape<T>& a, std::uint8_t kb, const PlacedShape<T>& b,
                                T margin) {
  const auto with = [&](auto kind) -> Manifold<T> {
    constexpr ShapeKind A = decltype(kind)::value;
    if constexpr ((M & shape_bit(A)) == 0)
      return {};
    else
      return detail::collide_with<M, A>(a, kb, b, margin);
  };
  switch (ka) {
    case sphere: return with(std::integral_constant<ShapeKind, sphere>{});
    case box: return with(std::integral_constant<ShapeKind, box>{});
    case plane: return with(std::integral_constant<ShapeKind, plane>{});
    case capsule: return with(std::integral_constant<ShapeKind, capsule>{});
    default: return {};
  }
}

// Body i of a Bodies view as the narrow phase reads it: only boxes and
// capsules need their rotation (a sphere's does not change its surface, a
// plane's lies in its parameters), so only theirs is loaded.
template <class T, class View>
GPUSOLVE_HD PlacedShape<T> placed_shape(const View& b, std::size_t i) {
  PlacedShape<T> s{math::Vector3<T>(b.pos(i, 0), b.pos(i, 1), b.pos(i, 2)), math::Matrix3x3<T>::identity(), {}};
  const std::uint8_t kind = b.shape[i];
  const std::size_t params = kind == plane ? 4 : kind == box ? 3 : kind == capsule ? 2 : 1;
  for (std::size_t c = 0; c < params; ++c) s.p[c] = b.shape_param(i, c);
  if (kind == box || kind == capsule)
    for (std::size_t c = 0; c < 9; ++c) s.R[c] = b.R(i, c);
  return s;
}

}  // namespace gpusolve::rbd
