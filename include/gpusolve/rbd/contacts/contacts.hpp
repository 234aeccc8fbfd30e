// Contacts: the structure-of-arrays store of all contacts of one time step (thesis Fig. 14).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocation_label.hpp"
#include "gpusolve/rbd/contact_models/contact_model.hpp"
#include "gpusolve/rbd/contacts/extent.hpp"
#include "gpusolve/container/logical_view.hpp"

namespace gpusolve::rbd {

// One entry per contact in every field; VectorD2 fields hold one component per
// row, so element (i, c) is component c of contact i (the layout of Bodies).
//
// Conventions (thesis 3.3): the normal n points from body b to body a; ra and rb
// go from each body's centre of mass to the contact point; phi0 is the gap along
// n at the start of the step (negative when the bodies overlap). The narrow phase
// fills a, b, n, ra, rb, phi0, bounce and, for models with friction, mu
// (View::set also builds the tangents). The solver fills dinv and x.
//
// Fields a model does not need (t, o, mu for Frictionless; spin and roll for
// a model without angular rows) are never allocated: their views are empty.
template <class Device, class T, class Model>
struct Contacts {
  static_assert(std::is_floating_point_v<T>, "Contacts: T must be float or double");
  using device_type = Device;
  using value_type = T;
  using model_type = Model;
  static constexpr std::size_t rows = Model::rows;
  static constexpr bool angular = Model::rows > Model::linear_rows;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;
  using VecD1 = D1<T>;
  using VecD2 = VectorD2<T, device_is<Device>>;

  D1<std::uint32_t> a, b;  // body indices
  D1<std::uint32_t> feature;  // ManifoldPoint::feature: which point of the pair's manifold
  VecD2 n, t, o;           // n x 3: normal (b -> a) and the two tangents
  VecD2 ra, rb;            // n x 3: centre of mass -> contact point
  VecD1 phi0;              // gap at the start of the step
  VecD1 mu;                // friction coefficient
  VecD1 spin, roll;        // torsional and rolling resistance, lengths (models with angular rows)
  VecD1 bounce;            // separation speed restitution asks for (0: none), materials.hpp
  VecD2 dinv;              // n x rows: the step of each row (the diagonal of D, InverseBlocks)
  VecD2 x;                 // n x rows: impulse (normal, t, o)
  VecD2 slip;              // n x 2: friction anchors (keep_anchors): a sticking point's slip along t and o

  Contacts() = default;
  explicit Contacts(std::size_t n) { resize(n); }

  // Sets the number of contacts. Storage only grows (geometrically), so a
  // step with fewer contacts than the last reuses it; contents are unspecified
  // afterwards.
  void resize(std::size_t count) {
    if (count > capacity_) {
      const memory::AllocationLabel label("contacts");
      std::size_t cap = capacity_ + capacity_ / 2;
      if (cap < count) cap = count;
      a.resize(cap);
      b.resize(cap);
      feature.resize(cap);
      phi0.resize(cap);
      bounce.resize(cap);
      for (VecD2* f : {&n, &ra, &rb}) f->resize(cap, 3);
      dinv.resize(cap, rows);
      x.resize(cap, rows);
      if constexpr (Model::friction) {
        t.resize(cap, 3);
        o.resize(cap, 3);
        mu.resize(cap);
      }
      if constexpr (angular) {
        spin.resize(cap);
        roll.resize(cap);
      }
      capacity_ = cap;
      if (anchored_) allocate_anchors();
    }
    n_ = count;
  }

  // Whether the contacts carry friction anchors (models with friction only;
  // World turns them on per ContactSettings::friction_anchors). Their storage
  // is allocated only while they are on.
  void keep_anchors(bool on) {
    anchored_ = on && Model::friction;
    if (anchored_ && slip.size_x() < capacity_) {
      const memory::AllocationLabel label("contacts");
      allocate_anchors();
    }
  }
  bool anchored() const { return anchored_; }
  std::size_t size() const { return n_; }
  std::size_t capacity() const { return capacity_; }

  // Where the count is known only to the backend (a step queued without a
  // host wait, World::advance_unattended): views carry size() as their bound
  // and read the count from *live in kernels; `expected` is the count the
  // host last knew, which sizes grids (never a loop). nullptr: size() is the count.
  void count_on_device(const std::uint32_t* live, std::size_t expected = 0) {
    live_ = live;
    expected_ = expected;
  }
  const std::uint32_t* live_count() const { return live_; }
  // The count, or where it is on the device, the count the host last knew.
  std::size_t expected_size() const { return live_ != nullptr ? expected_ : n_; }

  template <class E>
  using D1View = decltype(std::declval<D1<E>&>().view());
  using VecD1View = D1View<T>;
  using VecD2View = decltype(std::declval<VecD2&>().view());

  // Kernel-side handle: trivially copyable, passed by value to launch. Its
  // fields' extents are the logical size (the bound, where the count is on
  // the device), not the capacity. Host code sizes by bound(); kernels loop
  // to size().
  struct View {
    detail::Extent count;
    D1View<std::uint32_t> a, b, feature;
    VecD2View n, t, o, ra, rb;
    VecD1View phi0, mu, spin, roll, bounce;
    VecD2View dinv, x, slip;
    bool anchored;  // slip holds the friction anchors (keep_anchors)
    std::uint8_t unused[7] = {};  // no indeterminate bytes: a detection's graph key compares views byte by byte

    GPUSOLVE_HD std::size_t size() const {
#if !GPUSOLVE_DEVICE_CODE
      if constexpr (std::is_same_v<Device, device::gpu>)
        if (count.live != nullptr)
          throw UnsupportedError("gpusolve: Contacts::View::size() on the host while the count is on the device");
#endif
      return count.size();
    }
    std::size_t bound() const { return count.bound; }

    // A body pair's points are neighbours in the (a, b) order detection writes:
    // whether contacts i and j join the same two bodies, and whether contact i
    // is its pair's first point (a manifold's, or a compound pair's part pairs').
    GPUSOLVE_HD bool same_pair(std::size_t i, std::size_t j) const { return a[i] == a[j] && b[i] == b[j]; }
    GPUSOLVE_HD bool opens_pair(std::size_t i) const { return i == 0 || !same_pair(i - 1, i); }

    // Writes contact i. V is any vector type with operator[](0..2). The
    // tangents are built from n, so friction rows are well defined for any
    // normal; mu is ignored by models without friction. point_feature tells
    // the points of one body pair apart (warm starting matches it);
    // bounce_speed is the normal separation speed restitution asks for;
    // spinning and rolling (lengths) bound the angular rows of a model that has them.
    template <class V>
    GPUSOLVE_HD void set(std::size_t i, std::uint32_t body_a, std::uint32_t body_b, const V& normal,
                         const V& r_a, const V& r_b, T gap, T friction, std::uint32_t point_feature = 0,
                         T bounce_speed = T(0), T spinning = T(0), T rolling = T(0)) const {
      a[i] = body_a;
      b[i] = body_b;
      feature[i] = point_feature;
      for (std::size_t c = 0; c < 3; ++c) {
        n(i, c) = normal[c];
        ra(i, c) = r_a[c];
        rb(i, c) = r_b[c];
      }
      phi0[i] = gap;
      bounce[i] = bounce_speed;
      if constexpr (Model::friction) {
        mu[i] = friction;
        set_tangents(i);
      } else {
        (void)friction;
      }
      if constexpr (angular) {
        spin[i] = spinning;
        roll[i] = rolling;
      } else {
        (void)spinning, (void)rolling;
      }
    }

    // t = unit vector orthogonal to n (built against the axis n is least
    // aligned with, so it never degenerates), o = n x t.
    GPUSOLVE_HD void set_tangents(std::size_t i) const {
      const T nx = n(i, 0), ny = n(i, 1), nz = n(i, 2);
      T tx, ty, tz;
      if (std::fabs(nx) <= std::fabs(ny) && std::fabs(nx) <= std::fabs(nz)) {
        tx = T(0), ty = nz, tz = -ny;  // n x e_x
      } else if (std::fabs(ny) <= std::fabs(nz)) {
        tx = -nz, ty = T(0), tz = nx;  // n x e_y
      } else {
        tx = ny, ty = -nx, tz = T(0);  // n x e_z
      }
      const T inv = T(1) / std::sqrt(tx * tx + ty * ty + tz * tz);
      tx *= inv, ty *= inv, tz *= inv;
      t(i, 0) = tx, t(i, 1) = ty, t(i, 2) = tz;
      o(i, 0) = ny * tz - nz * ty;
      o(i, 1) = nz * tx - nx * tz;
      o(i, 2) = nx * ty - ny * tx;
    }
  };
  static_assert(std::is_trivially_copyable_v<View>);

  View view() {
    using gpusolve::detail::logical;
    return View{{n_, live_},
                logical(a.view(), n_),
                logical(b.view(), n_),
                logical(feature.view(), n_),
                logical(n.view(), n_),
                logical(t.view(), n_),
                logical(o.view(), n_),
                logical(ra.view(), n_),
                logical(rb.view(), n_),
                logical(phi0.view(), n_),
                logical(mu.view(), n_),
                logical(spin.view(), n_),
                logical(roll.view(), n_),
                logical(bounce.view(), n_),
                logical(dinv.view(), n_),
                logical(x.view(), n_),
                logical(slip.view(), n_),
                anchored_};
  }

 private:
  void allocate_anchors() { slip.resize(capacity_, 2); }

  bool anchored_ = false;
  std::size_t n_ = 0;
  std::size_t capacity_ = 0;
  const std::uint32_t* live_ = nullptr;
  std::size_t expected_ = 0;
};

}  // namespace gpusolve::rbd
