// Body: the host-side record of one rigid body, as a user's engine keeps it.
#pragma once

#include <array>
#include <cstdint>

#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

// Only the primary state lives here; the rotation matrix, the world-frame inverse
// inertia, the bounding sphere and the AABB are derived when the body is copied
// into a Bodies store. Matrices are row-major.
template <class T = float>
struct Body {
  BodyStatus status = active;
  ShapeKind shape = sphere;
  std::array<T, shape_param_rows> shape_param{};  // see shapes.hpp
  T inv_mass = 0;
  std::array<T, 9> inertia{};           // body frame; all zero for fixed bodies
  std::array<T, 9> inv_inertia_body{};  // body frame; all zero for fixed bodies
  std::array<T, 3> pos{};
  std::array<T, 4> q{1, 0, 0, 0};  // (w, x, y, z), as in gpusolve::math
  std::array<T, 3> v{}, w{}, force{}, torque{};
  T motion = 0;
  std::uint32_t first_part = 0;  // a compound's first part in its BodySet's parts()
  std::uint32_t material = 0;    // an id of its BodySet's materials() (0: the world's default)
};

}  // namespace gpusolve::rbd
