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

// The manifold of body a (kind ka) against body b (kind kb), with the kinds a
// scene holds in M; a kind outside M gives no points, and so does a compound,
// which is met part by part (body_manifolds.hpp). Not inlined on the
// device: the contact count and the contact write share one copy per M.
template <ShapeMask M = all_shapes, class T>
GPUSOLVE_HD_NOINLINE Manifold<T> collide(std::uint8_t ka, const PlacedShape<T>& a, std::uint8_t kb, const PlacedShape<T>& b,
                                T margin) {
  const auto none = [] { return Manifold<T>{}; };
  return visit_kind<Manifold<T>, M & primitives>(
      ka,
      [&](auto kind_a) {
        constexpr ShapeKind A = decltype(kind_a)::value;
        return visit_kind<Manifold<T>, M & primitives>(
            kb,
            [&](auto kind_b) -> Manifold<T> {
              constexpr ShapeKind B = decltype(kind_b)::value;
              if constexpr (A <= B)
                return ShapePair<A, B>::collide(a, b, margin);
              else
                return ShapePair<B, A>::collide(b, a, margin).flipped();
            },
            none);
      },
      none);
}

// Body i of a Bodies view as the narrow phase reads it: the parameter slots
// its kind reads, and its rotation only where its surface turns with it
// (ShapeTraits: boxes and capsules; a sphere's turn does not change its
// surface, a plane's lies in its parameters). A compound is met part by part
// (body_manifolds.hpp).
template <class T, class View>
GPUSOLVE_HD PlacedShape<T> placed_shape(const View& b, std::size_t i) {
  PlacedShape<T> s{math::Vector3<T>(b.pos(i, 0), b.pos(i, 1), b.pos(i, 2)), math::Matrix3x3<T>::identity(), {}};
  visit_kind<void, primitives>(
      b.shape[i],
      [&](auto kind) {
        using Traits = ShapeTraits<decltype(kind)::value>;
        for (std::size_t c = 0; c < Traits::params; ++c) s.p[c] = b.shape_param(i, c);
        if constexpr (Traits::rotated)
          for (std::size_t c = 0; c < 9; ++c) s.R[c] = b.R(i, c);
      },
      [] {});
  return s;
}

}  // namespace gpusolve::rbd
