// Time integration of the bodies (thesis 3.2, 5.1): forces and torques, the
// linear and angular moves, and the bounding-sphere AABB update.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies.hpp"

namespace gpusolve::rbd {

// Semi-implicit Euler, linear part (thesis MoveLinearKernel):
// v += dt (f / m + g), then x += dt v; the force is consumed.
template <class View, class T>
struct MoveLinear {
  View b;
  T dt;
  math::Vector3<T> gravity;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!b.moving(i)) return;
    const BodyOffsets<T> off(b);
    math::Vector3Global<T> v(b.v, off.v3, i), x(b.pos, off.v3, i), f(b.force, off.v3, i);
    v += dt * (b.inv_mass[i] * f + gravity);
    x += dt * v;
    f = math::Vector3<T>();
  }
};

// Angular part (thesis MoveAngularKernel): w += dt R I^-1 R^T (tau - w x (R I R^T w)),
// the gyroscopic term keeping a freely spinning body's angular momentum; then q
// turns by w dt and is renormalised. The torque is consumed.
template <class View, class T>
struct MoveAngular {
  View b;
  T dt;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!b.moving(i)) return;
    const BodyOffsets<T> off(b);
    math::Vector3Global<T> wg(b.w, off.v3, i), tau(b.torque, off.v3, i);
    math::QuaternionGlobal<T> q(b.q, off.q4, i);
    const math::Matrix3x3<T> R(math::Matrix3x3Global<T>(b.R, off.m9, i));
    const math::Matrix3x3<T> I = math::rotate_tensor(R, math::Matrix3x3Global<T>(b.inertia, off.m9, i));
    const math::Matrix3x3<T> Iinv(math::Matrix3x3Global<T>(b.inv_inertia, off.m9, i));
    const math::Vector3<T> w(wg);
    const math::Vector3<T> Iw = I * w;
    const math::Vector3<T> rhs = math::Vector3<T>(tau) - w % Iw;
    wg = w + dt * (Iinv * rhs);
    q = math::integrate_orientation(q, wg, dt);
    tau = math::Vector3<T>();
  }
};

// Everything that derives from position, orientation and shape (thesis
// UpdateBodyKernel): the rotation matrix, the world inverse inertia R I^-1 R^T,
// the bounding-sphere radius and its AABB; with track_motion, the motion
// average (|v| + |w| blended half and half with its previous value).
template <class View, class T>
struct UpdateBody {
  View b;
  std::size_t first;
  bool track_motion;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    const std::size_t i = first + k;
    const BodyOffsets<T> off(b);
    math::Matrix3x3Global<T> R(b.R, off.m9, i), Iinv(b.inv_inertia, off.m9, i);
    R = math::to_rotation_matrix(math::QuaternionGlobal<T>(b.q, off.q4, i));
    Iinv = math::rotate_tensor(R, math::Matrix3x3Global<T>(b.inv_inertia_body, off.m9, i));
    const T r = bounding_radius(i);
    b.radius[i] = r;
    for (std::size_t c = 0; c < 3; ++c) {
      b.aabb(i, c) = b.pos(i, c) - r;
      b.aabb(i, c + 3) = b.pos(i, c) + r;
    }
    if (track_motion) {
      const T speed = math::norm(math::Vector3Global<T>(b.v, off.v3, i)) +
                      math::norm(math::Vector3Global<T>(b.w, off.v3, i));
      b.motion[i] = (b.motion[i] + speed) / 2;
    }
  }
  GPUSOLVE_HD T bounding_radius(std::size_t i) const {
    switch (b.shape[i]) {
      case sphere:
        return b.shape_param(i, 0);
      case box: {
        const T x = b.shape_param(i, 0), y = b.shape_param(i, 1), z = b.shape_param(i, 2);
        return std::sqrt(x * x + y * y + z * z);
      }
      default:  // a plane bounds nothing
        return std::numeric_limits<T>::infinity();
    }
  }
};

// Recomputes the derived fields of bodies [first, last) without touching motion
// (after bodies were set from outside, e.g. by the BodyManager).
template <class Device, class View>
void update_derived(Device dev, const View& b, std::size_t first, std::size_t last,
                    stream_t stream = stream_t{}) {
  using T = std::remove_cv_t<std::remove_reference_t<decltype(b.pos(0, 0))>>;
  if (last > first) launch(dev, last - first, UpdateBody<View, T>{b, first, false}, stream);
}

// One time step of size dt for every active body on the bodies' backend:
// external forces (the force and torque fields plus gravity), linear and
// angular moves, then the derived fields and motion. Fixed and removed bodies
// do not move. Forces and torques are zero afterwards.
template <class Device, class T>
void integrate(Bodies<Device, T>& bodies, T dt, const math::Vector3<T>& gravity,
               stream_t stream = stream_t{}) {
  using View = typename Bodies<Device, T>::View;
  const View b = bodies.view();
  const std::size_t n = b.size();
  if (n == 0) return;
  launch(Device{}, n, MoveLinear<View, T>{b, dt, gravity}, stream);
  launch(Device{}, n, MoveAngular<View, T>{b, dt}, stream);
  launch(Device{}, n, UpdateBody<View, T>{b, 0, true}, stream);
}

}  // namespace gpusolve::rbd
