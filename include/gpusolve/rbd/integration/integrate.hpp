// Time integration of the bodies (thesis 3.2, 5.1): the velocity change of
// forces and torques, the linear and angular moves, the bounding-sphere AABB update.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/bodies/derived_fields.hpp"

namespace gpusolve::rbd {

// The velocity change of the step's external forces (semi-implicit Euler, the
// velocity half of thesis MoveLinearKernel and MoveAngularKernel):
// v += dt (f / m + g), w += dt R I^-1 R^T (tau - w x (R I R^T w)). The
// gyroscopic term -w x I w keeps a freely spinning body's angular momentum; it
// belongs here, with the other velocity-dependent external terms, so that a
// contact solve after this sees (and constrains) the whole unconstrained
// velocity v + dt M^-1 f (thesis Eq. 6). Force and torque are consumed.
template <class View, class T>
struct ApplyForces {
  View b;
  T dt;
  math::Vector3<T> gravity;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!b.moving(i)) return;
    const BodyOffsets<T> off(b);
    math::Vector3Global<T> v(b.v, off.v3, i), f(b.force, off.v3, i);
    v += dt * (b.inv_mass[i] * f + gravity);
    f = math::Vector3<T>();
    math::Vector3Global<T> wg(b.w, off.v3, i), tau(b.torque, off.v3, i);
    const math::Matrix3x3<T> R(math::Matrix3x3Global<T>(b.R, off.m9, i));
    const math::Matrix3x3<T> I = math::rotate_tensor(R, math::Matrix3x3Global<T>(b.inertia, off.m9, i));
    const math::Matrix3x3<T> Iinv(math::Matrix3x3Global<T>(b.inv_inertia, off.m9, i));
    const math::Vector3<T> w(wg);
    const math::Vector3<T> Iw = I * w;
    const math::Vector3<T> rhs = math::Vector3<T>(tau) - w % Iw;
    wg = w + dt * (Iinv * rhs);
    tau = math::Vector3<T>();
  }
};

// The position half: x += dt v, and q turns by w dt and is renormalised.
template <class View, class T>
struct Move {
  View b;
  T dt;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!b.moving(i)) return;
    const BodyOffsets<T> off(b);
    math::Vector3Global<T> v(b.v, off.v3, i), x(b.pos, off.v3, i), w(b.w, off.v3, i);
    math::QuaternionGlobal<T> q(b.q, off.q4, i);
    x += dt * v;
    q = math::integrate_orientation(q, w, dt);
  }
};

// Move, then UpdateBody with motion, of one body: one launch for both, since
// a body's derived fields read only its own new state.
template <class View, class T>
struct MoveBody {
  Move<View, T> move;
  UpdateBody<View, T> update;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    move(i);
    update(i);
  }
};

// The external forces (the force and torque fields plus gravity) of a step of
// size dt, on the velocities of every active body. Forces and torques are zero
// afterwards. World::step calls it before the contact solve.
template <class Device, class T>
void apply_forces(Bodies<Device, T>& bodies, T dt, const math::Vector3<T>& gravity, stream_t stream = stream_t{}) {
  using View = typename Bodies<Device, T>::View;
  const View b = bodies.view();
  if (b.size() != 0) launch(Device{}, b.size(), ApplyForces<View, T>{b, dt, gravity}, stream);
}

// Body i's move over dt and its derived fields, as one functor (move()'s
// kernel, for a caller that fuses it with its own per-body work).
template <class View, class T>
MoveBody<View, T> body_move(const View& b, T dt) {
  return {{b, dt}, {b, 0, true}};
}

// Moves every active body by its velocities over dt, then updates the derived
// fields and motion of all bodies. Fixed and removed bodies do not move.
// World::step calls it after the contact solve (fused with the step's figures).
template <class Device, class T>
void move(Bodies<Device, T>& bodies, T dt, stream_t stream = stream_t{}) {
  using View = typename Bodies<Device, T>::View;
  const View b = bodies.view();
  if (b.size() == 0) return;
  launch(Device{}, b.size(), body_move(b, dt), stream);
}

// One unconstrained time step (no contacts): apply_forces, then move.
template <class Device, class T>
void integrate(Bodies<Device, T>& bodies, T dt, const math::Vector3<T>& gravity, stream_t stream = stream_t{}) {
  apply_forces(bodies, dt, gravity, stream);
  move(bodies, dt, stream);
}

}  // namespace gpusolve::rbd
