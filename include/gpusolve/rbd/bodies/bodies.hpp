// Bodies: the structure-of-arrays store of all rigid bodies on one backend (thesis Fig. 12).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/container/vector_d2_offset.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/container/logical_view.hpp"
#include "gpusolve/rbd/bodies/materials.hpp"
#include "gpusolve/rbd/bodies/parts.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

// One entry per body in every field; VectorD2 fields hold one component per row,
// so element (i, c) is component c of body i and consecutive threads read
// consecutive bodies. 3x3 matrices are row-major in 9 rows: (i, 3*r + c).
// Quaternions are (w, x, y, z), as in gpusolve::math.
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
  VecD2 inertia;            // n x 9, body frame (the turn keeps L = R I R^T w)
  VecD2 inv_inertia_body;   // n x 9, body frame; 0 for fixed bodies
  VecD2 inv_inertia;        // n x 9, world frame R I^-1 R^T
  VecD2 pos;                // n x 3, centre of mass (planes: the point n*d)
  VecD2 q;                  // n x 4, unit orientation quaternion (w, x, y, z)
  VecD2 R;                  // n x 9, rotation matrix of q (body -> world)
  VecD2 v;                  // n x 3, linear velocity
  VecD2 w;                  // n x 3, angular velocity (world frame)
  VecD2 force;              // n x 3, external force applied in the next integration
  VecD2 torque;             // n x 3, external torque applied in the next integration
  VecD1 radius;             // bounding-sphere radius (planes: +infinity)
  VecD2 aabb;               // n x 6: (min x, y, z, max x, y, z) of the bounding sphere
  VecD1 motion;             // running average of |v| + |w| (sleep heuristics, statistics)
  D1<std::uint32_t> first_part;  // a compound's first row of `parts` (others: 0)
  D1<std::uint32_t> material;    // material id (materials.hpp; 0: the world's default)
  // The pair table of the materials (not one per body).
  MaterialPairs<Device, T> materials;
  // The parts of the compounds, not one per body (parts.hpp).
  Parts<Device, T> parts;
  // The shape kinds among the bodies (host side): collision detection compiles
  // in the pairs of these only (a compound's parts' kinds among them).
  // BodyManager keeps it exact; a store filled by
  // hand says all_shapes unless told less.
  ShapeMask shapes = all_shapes;

  Bodies() = default;
  explicit Bodies(std::size_t n) { resize(n); }

  // Sets the number of bodies. Storage only grows: within capacity() the
  // contents are kept; beyond it every field is reallocated (all zero after).
  // Returns whether it reallocated.
  bool resize(std::size_t count) {
    const bool grow = count > capacity_;
    if (grow) {
      zip_fields(*this, *this, [count](auto& f, auto&, std::size_t rows, bool) {
        if constexpr (std::remove_reference_t<decltype(f)>::rank == 1)
          f.resize(count);
        else
          f.resize(count, rows);
      });
      capacity_ = count;
    }
    n_ = count;
    return grow;
  }
  std::size_t size() const { return n_; }
  std::size_t capacity() const { return capacity_; }

  // Copies every field from a store on any backend (same capacity after).
  template <class D2>
  Bodies& operator=(const Bodies<D2, T>& o) {
    if (capacity_ != o.capacity()) *this = Bodies(o.capacity());
    n_ = o.size();
    shapes = o.shapes;
    parts = o.parts;
    materials = o.materials;
    zip_fields(*this, o, [](auto& dst, const auto& src, std::size_t, bool) { dst = src; });
    return *this;
  }

  template <class E>
  using D1View = decltype(std::declval<D1<E>&>().view());
  using VecD1View = D1View<T>;
  using VecD2View = decltype(std::declval<VecD2&>().view());

  // Kernel-side handle: trivially copyable, passed by value to launch. Its
  // extents are the logical size, not the capacity.
  struct View {
    std::size_t count;
    D1View<std::uint8_t> status, shape;
    VecD2View shape_param;
    VecD1View inv_mass;
    VecD2View inertia, inv_inertia_body, inv_inertia, pos, q, R, v, w, force, torque;
    VecD1View radius;
    VecD2View aabb;
    VecD1View motion;
    D1View<std::uint32_t> first_part, material;
    typename MaterialPairs<Device, T>::View materials;
    typename Parts<Device, T>::View parts;

    GPUSOLVE_HD std::size_t size() const { return count; }
    // A body that the integrator moves.
    GPUSOLVE_HD bool moving(std::size_t i) const { return moves(status[i]); }
  };
  static_assert(std::is_trivially_copyable_v<View>);

  View view() {
    using gpusolve::detail::logical;
    return View{n_,
                logical(status.view(), n_),
                logical(shape.view(), n_),
                logical(shape_param.view(), n_),
                logical(inv_mass.view(), n_),
                logical(inertia.view(), n_),
                logical(inv_inertia_body.view(), n_),
                logical(inv_inertia.view(), n_),
                logical(pos.view(), n_),
                logical(q.view(), n_),
                logical(R.view(), n_),
                logical(v.view(), n_),
                logical(w.view(), n_),
                logical(force.view(), n_),
                logical(torque.view(), n_),
                logical(radius.view(), n_),
                logical(aabb.view(), n_),
                logical(motion.view(), n_),
                logical(first_part.view(), n_),
                logical(material.view(), n_),
                materials.view(),
                parts.view()};
  }

 private:
  std::size_t n_ = 0;
  std::size_t capacity_ = 0;
};

// The row offsets of one Bodies store (all its VectorD2 fields share a pitch).
template <class T>
struct BodyOffsets {
  VectorD2Offset<3> v3;
  VectorD2Offset<4> q4;
  VectorD2Offset<9> m9;
  template <class View>
  GPUSOLVE_HD explicit BodyOffsets(const View& b) : v3(b.pos.pitch), q4(b.q.pitch), m9(b.R.pitch) {}
};

// Calls f(field of a, same field of b, rows, per_step) for every field of two
// stores (possibly the same one, possibly on different backends). per_step marks
// what changes every time step (thesis 5.1.2): state, forces and what is derived
// from position and orientation; the rest (shape, mass, inertia) is set once.
template <class A, class B, class F>
void zip_fields(A& a, B& b, F&& f) {
  f(a.status, b.status, 1, true);
  f(a.shape, b.shape, 1, false);
  f(a.shape_param, b.shape_param, shape_param_rows, false);
  f(a.inv_mass, b.inv_mass, 1, false);
  f(a.inertia, b.inertia, 9, false);
  f(a.inv_inertia_body, b.inv_inertia_body, 9, false);
  f(a.inv_inertia, b.inv_inertia, 9, true);
  f(a.pos, b.pos, 3, true);
  f(a.q, b.q, 4, true);
  f(a.R, b.R, 9, true);
  f(a.v, b.v, 3, true);
  f(a.w, b.w, 3, true);
  f(a.force, b.force, 3, true);
  f(a.torque, b.torque, 3, true);
  f(a.radius, b.radius, 1, false);
  f(a.aabb, b.aabb, 6, true);
  f(a.motion, b.motion, 1, true);
  f(a.first_part, b.first_part, 1, false);
  f(a.material, b.material, 1, false);
}

}  // namespace gpusolve::rbd
