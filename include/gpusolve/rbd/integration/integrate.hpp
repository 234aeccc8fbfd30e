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
// v += dt (f / m + g), w += dt R I^-1 R^T tau, the velocity a contact solve
// after this sees (thesis Eq. 6). The gyroscopic part of Euler's equations is
// not here: Move turns the angular momentum with the body (below), which keeps
// it exactly. Force and torque are consumed.
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
    math::Vector3Global<T> w(b.w, off.v3, i), tau(b.torque, off.v3, i);
    w += dt * (math::Matrix3x3<T>(math::Matrix3x3Global<T>(b.inv_inertia, off.m9, i)) * math::Vector3<T>(tau));
    tau = math::Vector3<T>();
  }
};

// Whether body i's inertia is the same about every axis (spheres, cubes): its
// angular velocity and momentum then turn together and need no remapping.
template <class View, class T>
GPUSOLVE_HD bool isotropic_inertia(const View& b, std::size_t i) {
  return b.inertia(i, 1) == 0 && b.inertia(i, 2) == 0 && b.inertia(i, 5) == 0 && b.inertia(i, 0) == b.inertia(i, 4) &&
         b.inertia(i, 0) == b.inertia(i, 8);
}

// The angular velocity R I^-1 R^T L of angular momentum L (world frame) at
// the orientation q, with the body-frame inverse inertia Iinv.
template <class T>
GPUSOLVE_HD math::Vector3<T> velocity_of_momentum(const math::Quaternion<T>& q, const math::Matrix3x3<T>& Iinv,
                                                  const math::Vector3<T>& L) {
  const math::Matrix3x3<T> R = math::to_rotation_matrix(q);
  const math::Vector3<T> L_body(math::transpose(R) * L);
  const math::Vector3<T> w_body(Iinv * L_body);
  return math::Vector3<T>(R * w_body);
}

// The position half: x += dt v, and q turns by w dt (the exact exponential
// map, renormalised). A body whose inertia differs between axes keeps its
// world angular momentum L = R I R^T w across the turn: w afterwards is
// R' I^-1 R'^T L at the new orientation R' (the gyroscopic precession, as
// Box2D v3 and Jolt keep L), and the turn takes the mean of w before and of
// that w at a first guess of R' (a trapezoidal step: the rotational energy's
// drift is second order in dt). R is still the old orientation here
// (UpdateBody writes the new one after).
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
    if (isotropic_inertia<View, T>(b, i)) {
      q = math::integrate_orientation(q, w, dt);
      return;
    }
    const math::Quaternion<T> q0(q);
    const math::Vector3<T> w0(w);
    const math::Matrix3x3<T> I(math::Matrix3x3Global<T>(b.inertia, off.m9, i));
    const math::Matrix3x3<T> before(math::Matrix3x3Global<T>(b.R, off.m9, i));
    const math::Vector3<T> w0_body(math::transpose(before) * w0);
    const math::Vector3<T> L_body(I * w0_body);
    const math::Vector3<T> L(before * L_body);  // world frame: what the turn keeps
    const math::Matrix3x3<T> Iinv(math::Matrix3x3Global<T>(b.inv_inertia_body, off.m9, i));
    const math::Vector3<T> w_guess = velocity_of_momentum(math::integrate_orientation(q0, w0, dt), Iinv, L);
    const math::Vector3<T> w_mean(T(0.5) * (w0 + w_guess));
    const math::Quaternion<T> q1 = math::integrate_orientation(q0, w_mean, dt);
    q = q1;
    w = velocity_of_momentum(q1, Iinv, L);
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
