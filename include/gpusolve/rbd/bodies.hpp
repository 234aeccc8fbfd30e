// Bodies: the structure-of-arrays store of all rigid bodies on one backend (thesis Fig. 12).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/rbd/shapes.hpp"

namespace gpusolve::rbd {

// One entry per body in every field; VectorD2 fields hold one component per row,
// so element (i, c) is component c of body i and consecutive threads read
// consecutive bodies. 3x3 matrices are stored row-major in 9 rows: (i, 3*r + c).
template <class Device, class T = float>
struct Bodies {
  static_assert(std::is_floating_point_v<T>, "Bodies: T must be float or double");
  using device_type = Device;
  using value_type = T;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;
  using VecD1 = D1<T>;
  using VecD2 = VectorD2<T, device_is<Device>>;

  D1<std::uint8_t> status;  // BodyStatus
  D1<std::uint8_t> shape;   // ShapeKind
  VecD2 shape_param;        // n x 4, see shapes.hpp
  VecD1 inv_mass;           // 0 for fixed bodies
  VecD2 inertia;            // n x 9, body frame (needed by the gyroscopic term)
  VecD2 inv_inertia_body;   // n x 9, body frame; 0 for fixed bodies
  VecD2 inv_inertia;        // n x 9, world frame R I^-1 R^T
  VecD2 pos;                // n x 3, centre of mass (planes: the point n*d)
  VecD2 q;                  // n x 4, orientation quaternion (x, y, z, w), unit length
  VecD2 R;                  // n x 9, rotation matrix of q
  VecD2 v;                  // n x 3, linear velocity
  VecD2 w;                  // n x 3, angular velocity (world frame)
  VecD2 force;              // n x 3, external force applied in the next integration
  VecD2 torque;             // n x 3, external torque applied in the next integration
  VecD1 radius;             // bounding-sphere radius (planes: +infinity)
  VecD2 aabb;               // n x 6: (min x, y, z, max x, y, z) of the bounding sphere
  VecD1 motion;             // running average of |v| + |w| (sleep heuristics, statistics)

  Bodies() = default;
  explicit Bodies(std::size_t n) { resize(n); }

  // Reallocates every field for n bodies; contents are unspecified afterwards.
  void resize(std::size_t n) {
    n_ = n;
    for_each_d1([n](auto& f) { f.resize(n); });
    for_each_d2([n](auto& f, std::size_t rows) { f.resize(n, rows); });
  }
  std::size_t size() const { return n_; }

  // Copies every field from another backend (assignment between host and device).
  template <class D2>
  Bodies& operator=(const Bodies<D2, T>& o) {
    n_ = o.size();
    status = o.status; shape = o.shape; shape_param = o.shape_param; inv_mass = o.inv_mass;
    inertia = o.inertia; inv_inertia_body = o.inv_inertia_body; inv_inertia = o.inv_inertia;
    pos = o.pos; q = o.q; R = o.R; v = o.v; w = o.w; force = o.force; torque = o.torque;
    radius = o.radius; aabb = o.aabb; motion = o.motion;
    return *this;
  }

  // Kernel-side handle: trivially copyable, passed by value to launch.
  template <class E>
  using D1View = decltype(std::declval<D1<E>&>().view());
  using VecD1View = D1View<T>;
  using VecD2View = decltype(std::declval<VecD2&>().view());
  struct View {
    std::size_t n;
    D1View<std::uint8_t> status, shape;
    VecD2View shape_param;
    VecD1View inv_mass;
    VecD2View inertia, inv_inertia_body, inv_inertia, pos, q, R, v, w, force, torque;
    VecD1View radius;
    VecD2View aabb;
    VecD1View motion;
  };
  View view() {
    return View{n_,      status.view(), shape.view(),  shape_param.view(), inv_mass.view(),
                inertia.view(), inv_inertia_body.view(), inv_inertia.view(), pos.view(),
                q.view(), R.view(), v.view(), w.view(), force.view(), torque.view(),
                radius.view(), aabb.view(), motion.view()};
  }

  // Visits every VectorD2 field with its number of rows (used by resize and the BodyManager).
  template <class F>
  void for_each_d2(F&& f) {
    f(shape_param, shape_param_rows); f(inertia, 9); f(inv_inertia_body, 9); f(inv_inertia, 9);
    f(pos, 3); f(q, 4); f(R, 9); f(v, 3); f(w, 3); f(force, 3); f(torque, 3); f(aabb, 6);
  }
  template <class F>
  void for_each_d1(F&& f) {
    f(status); f(shape); f(inv_mass); f(radius); f(motion);
  }

 private:
  std::size_t n_ = 0;
};

}  // namespace gpusolve::rbd
