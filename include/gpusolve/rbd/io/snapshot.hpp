// snapshot: the Frame of a host BodySet (what the frame writers draw), removed bodies left out.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/io/frame.hpp"

namespace gpusolve::rbd::io {

namespace detail {

// How each kind a frame holds is drawn: one overload per kind a compound's
// part or a body alone can be, at centre p, rotation R (body -> world), shape
// parameters s; a moving one is drawn with the moving bodies.
template <class T>
void draw(Frame& f, KindConstant<sphere>, const Frame::Vec3& p, const math::Matrix3x3<T>&,
          const std::array<T, shape_param_rows>& s, bool, const Frame::Vec3& v) {
  f.add_sphere(p, s[0], v);
}
template <class T>
void draw(Frame& f, KindConstant<box>, const Frame::Vec3& p, const math::Matrix3x3<T>& R,
          const std::array<T, shape_param_rows>& s, bool moving, const Frame::Vec3&) {
  Frame::Box x{p, {double(s[0]), double(s[1]), double(s[2])}, {}, moving};
  for (int k = 0; k < 9; ++k) x.R[k] = R[k];
  f.boxes.push_back(x);
}
template <class T>
void draw(Frame& f, KindConstant<capsule>, const Frame::Vec3& p, const math::Matrix3x3<T>& R,
          const std::array<T, shape_param_rows>& s, bool, const Frame::Vec3&) {
  f.capsules.push_back({p, {double(R(0, 0)), double(R(1, 0)), double(R(2, 0))}, double(s[0]), double(s[1])});
}
template <class T>
void draw(Frame& f, KindConstant<plane>, const Frame::Vec3&, const math::Matrix3x3<T>&,
          const std::array<T, shape_param_rows>& s, bool, const Frame::Vec3&) {
  f.planes.push_back({{double(s[0]), double(s[1]), double(s[2])}, double(s[3])});
}

// Adds one shape other than a compound to the frame (a kind without its draw
// overload does not compile).
template <class T>
void add_primitive(Frame& f, std::uint8_t shape, const Frame::Vec3& p, const math::Matrix3x3<T>& R,
                   const std::array<T, shape_param_rows>& s, bool moving, const Frame::Vec3& v) {
  visit_kind<void, primitives>(
      shape, [&](auto kind) { draw(f, kind, p, R, s, moving, v); }, [] {});
}

}  // namespace detail

// Every body as its primitives (a compound as its parts, each at its place).
template <class T>
Frame snapshot(const BodySet<T>& bodies, std::size_t step, double time) {
  Frame f;
  f.step = step;
  f.time = time;
  for (const auto& b : bodies.records()) {
    if (b.status == removed) continue;
    const Frame::Vec3 p{double(b.pos[0]), double(b.pos[1]), double(b.pos[2])};
    const Frame::Vec3 v{double(b.v[0]), double(b.v[1]), double(b.v[2])};
    const auto R = math::to_rotation_matrix(math::Quaternion<T>(b.q[0], b.q[1], b.q[2], b.q[3]));
    const bool moving = moves(b.status);
    if (b.shape != compound) {
      detail::add_primitive(f, b.shape, p, R, b.shape_param, moving, v);
      continue;
    }
    for (std::size_t k = 0; k < std::size_t(b.shape_param[0]); ++k) {
      const Part<T>& part = bodies.parts()[b.first_part + k];
      const math::Vector3<T> offset(part.pos[0], part.pos[1], part.pos[2]);
      const math::Vector3<T> x(R * offset);
      const auto Rk = math::to_rotation_matrix(math::Quaternion<T>(part.q[0], part.q[1], part.q[2], part.q[3]));
      detail::add_primitive(f, part.shape, {p[0] + x[0], p[1] + x[1], p[2] + x[2]}, math::Matrix3x3<T>(R * Rk),
                            part.shape_param, moving, v);
    }
  }
  return f;
}

}  // namespace gpusolve::rbd::io
