// Shape kinds and body states of the rigid-body solver, and the parameter slots of each shape.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gpusolve::rbd {

// What a body is doing. Fixed bodies never move (inverse mass and inertia are 0);
// removed bodies keep their slot until the BodyManager rebuilds (thesis 5.1.2).
enum BodyStatus : std::uint8_t { active = 0, fixed = 1, removed = 2 };

// pe's primitives (thesis 3.1). Every one moves or is fixed, except planes,
// which are always fixed.
enum ShapeKind : std::uint8_t { sphere = 0, box = 1, plane = 2, capsule = 3 };
inline constexpr int shape_kinds = 4;

// Number of shape parameters per body (rows of Bodies::shape_param):
//   sphere:  (radius, 0, 0, 0)
//   box:     (half extent x, y, z, 0) in the body frame
//   plane:   (unit normal x, y, z, offset d) in the world frame; points x with n.x = d
//            lie on it, the half-space n.x < d is solid.
//   capsule: (radius, half length, 0, 0): the points within the radius of the
//            segment from -half length to +half length along the body x axis.
inline constexpr std::size_t shape_param_rows = 4;

// A set of shape kinds, one bit each: which kinds a scene holds, so that
// detection compiles in no more pairs than the scene needs.
using ShapeMask = std::uint32_t;
inline constexpr ShapeMask shape_bit(ShapeKind k) { return ShapeMask(1) << k; }
inline constexpr ShapeMask all_shapes = (ShapeMask(1) << shape_kinds) - 1;
inline constexpr ShapeMask spheres_and_planes = shape_bit(sphere) | shape_bit(plane);

}  // namespace gpusolve::rbd
