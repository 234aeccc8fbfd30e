// Shape kinds and body states of the rigid-body solver, and the parameter slots of each shape.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// What a body is doing. Fixed bodies never move (inverse mass and inertia are 0);
// removed bodies keep their slot until the BodyManager rebuilds (thesis 5.1.2).
enum BodyStatus : std::uint8_t { active = 0, fixed = 1, removed = 2 };

// pe's primitives (thesis 3.1) and its Union, here `compound`: one rigid body
// made of sphere, box and capsule parts (parts.hpp). Every one moves or is
// fixed, except planes, which are always fixed.
enum ShapeKind : std::uint8_t { sphere = 0, box = 1, plane = 2, capsule = 3, compound = 4 };
inline constexpr int shape_kinds = 5;
// Each kind's name, by its value (for messages).
inline constexpr const char* shape_names[shape_kinds] = {"sphere", "box", "plane", "capsule", "compound"};

// Number of shape parameters per body (rows of Bodies::shape_param):
//   sphere:  (radius, 0, 0, 0)
//   box:     (half extent x, y, z, 0) in the body frame
//   plane:   (unit normal x, y, z, offset d) in the world frame; points x with n.x = d
//            lie on it, the half-space n.x < d is solid.
//   capsule: (radius, half length, 0, 0): the points within the radius of the
//            segment from -half length to +half length along the body x axis.
//   compound: (number of parts, bounding radius, smallest feature size, 0),
//            set by BodySet::add_compound from its parts; the parts are
//            Bodies::parts [first_part, first_part + number).
inline constexpr std::size_t shape_param_rows = 4;

// A part of a compound is a sphere, a box or a capsule.
GPUSOLVE_HD constexpr bool part_kind(std::uint8_t k) { return k == sphere || k == box || k == capsule; }

// The radius of the smallest sphere about a primitive's centre that holds it
// (p: its shape parameters); a plane bounds nothing (+infinity).
template <class T>
GPUSOLVE_HD T primitive_bound(std::uint8_t kind, T p0, T p1, T p2) {
  switch (kind) {
    case sphere: return p0;
    case box: return std::sqrt(p0 * p0 + p1 * p1 + p2 * p2);
    case capsule: return p0 + p1;
    default: return std::numeric_limits<T>::infinity();
  }
}

// The size penetration is measured against (statistics/accuracy.hpp), defined
// once: a sphere's or capsule's radius, a box's smallest half extent; a plane
// has none (+infinity), so a body on a plane is measured against the body.
template <class T>
GPUSOLVE_HD T primitive_feature_size(std::uint8_t kind, T p0, T p1, T p2) {
  switch (kind) {
    case box: {
      const T xy = p0 < p1 ? p0 : p1;
      return xy < p2 ? xy : p2;
    }
    case plane: return std::numeric_limits<T>::infinity();
    default: return p0;  // sphere, capsule
  }
}

// A set of shape kinds, one bit each: which kinds a scene holds, so that
// detection compiles in no more pairs than the scene needs.
using ShapeMask = std::uint32_t;
inline constexpr ShapeMask shape_bit(ShapeKind k) { return ShapeMask(1) << k; }
inline constexpr ShapeMask all_shapes = (ShapeMask(1) << shape_kinds) - 1;
inline constexpr ShapeMask spheres_and_planes = shape_bit(sphere) | shape_bit(plane);
// The kinds a pair of parts can be: all but compound (compounds do not nest).
inline constexpr ShapeMask primitives = all_shapes & ~shape_bit(compound);

}  // namespace gpusolve::rbd
