// Shape kinds and body states of the rigid-body solver, and the parameter slots of each shape.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gpusolve::rbd {

// What a body is doing. Fixed bodies never move (inverse mass and inertia are 0);
// removed bodies keep their slot until the BodyManager rebuilds (thesis 5.1.2).
enum BodyStatus : std::uint8_t { active = 0, fixed = 1, removed = 2 };

// The geometric primitives the scenes use. Boxes and planes are always fixed.
enum ShapeKind : std::uint8_t { sphere = 0, box = 1, plane = 2 };

// Number of shape parameters per body (rows of Bodies::shape_param):
//   sphere: (radius, 0, 0, 0)
//   box:    (half extent x, y, z, 0) in the body frame
//   plane:  (unit normal x, y, z, offset d) in the world frame; points x with n.x = d
//           lie on it, the half-space n.x < d is solid.
inline constexpr std::size_t shape_param_rows = 4;

}  // namespace gpusolve::rbd
