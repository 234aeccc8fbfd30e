// Collision detection where the bodies live: the broad phase for sphere pairs,
// every active sphere against the few obstacles (planes, boxes), the narrow
// phase, and the contacts written by a count pass, a scan and a write pass.
#pragma once

#include <cstddef>
#include <cstdint>

#include <thrust/binary_search.h>
#include <thrust/copy.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/scan.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/collision/broad_phase.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/collision/narrow_phase.hpp"
#include "gpusolve/rbd/detail/scratch.hpp"
#include "gpusolve/rbd/detail/thrust_backend.hpp"

namespace gpusolve::rbd {
namespace detail {

template <class View>
struct IsObstacle {  // a plane or box taking part
  View b;
  GPUSOLVE_HD bool operator()(std::uint32_t i) const { return b.shape[i] != sphere && b.status[i] != removed; }
};

struct FirstKeyOf {  // the smallest pair key with a == i
  GPUSOLVE_HD std::uint64_t operator()(std::uint32_t i) const { return pair_key(i, 0); }
};

// Visits the contacts of sphere i as body a, in increasing order of body b:
// its grid pairs (a fixed sphere only with active ones) merged with the
// obstacles (active spheres only). visit(b, geometry) for every gap < margin.
template <class View, class T>
struct ContactWalk {
  View b;
  T margin;
  const std::uint64_t* pairs;       // pair keys sorted
  const std::uint32_t* pair_start;  // n + 1 entries: pairs of body i are [pair_start[i], pair_start[i + 1])
  const std::uint32_t* obstacles;   // sorted body indices
  std::uint32_t obstacle_count;

  template <class F>
  GPUSOLVE_HD void operator()(std::size_t i, F&& visit) const {
    if (!on_grid(b, i)) return;
    const bool active_a = b.status[i] == active;
    const BodyOffsets<T> off(b);
    const math::Vector3<T> pa(math::Vector3Global<T>(b.pos, off.v3, i));
    const T Ra = b.radius[i];
    std::uint32_t p = pair_start[i];
    const std::uint32_t pe = pair_start[i + 1];
    std::uint32_t k = 0;
    const std::uint32_t ke = active_a ? obstacle_count : 0;
    while (p < pe || k < ke) {
      const bool take_pair = k >= ke || (p < pe && pair_b(pairs[p]) < obstacles[k]);
      const std::uint32_t j = take_pair ? pair_b(pairs[p++]) : obstacles[k++];
      if (take_pair && !active_a && b.status[j] != active) continue;
      const math::Vector3<T> pb(math::Vector3Global<T>(b.pos, off.v3, j));
      ContactGeometry<T> g;
      if (b.shape[j] == sphere) {
        g = sphere_sphere(pa, Ra, pb, b.radius[j]);
      } else if (b.shape[j] == plane) {
        const math::Vector3<T> n(b.shape_param(j, 0), b.shape_param(j, 1), b.shape_param(j, 2));
        g = sphere_plane(pa, Ra, n, b.shape_param(j, 3), pb);
      } else {
        const math::Vector3<T> h(b.shape_param(j, 0), b.shape_param(j, 1), b.shape_param(j, 2));
        g = sphere_box(pa, Ra, pb, math::Matrix3x3<T>(math::Matrix3x3Global<T>(b.R, off.m9, j)), h);
      }
      if (g.gap < margin) visit(j, g);
    }
  }
};

template <class Walk>
struct CountContacts {
  Walk walk;
  std::uint32_t* count;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t c = 0;
    walk(i, [&c](std::uint32_t, const auto&) { ++c; });
    count[i] = c;
  }
};

template <class Walk, class ContactView, class T>
struct WriteContacts {
  Walk walk;
  const std::uint32_t* offset;  // inclusive scan of the counts
  const std::uint32_t* count;
  ContactView contacts;
  T mu;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t o = offset[i] - count[i];
    walk(i, [&](std::uint32_t j, const ContactGeometry<T>& g) {
      contacts.set(o++, std::uint32_t(i), j, g.n, g.ra, g.rb, g.gap, mu);
    });
  }
};

}  // namespace detail

// Rebuilds the contacts of the bodies every step, on their backend. A contact
// is made wherever two surfaces are closer than `margin` (not only where they
// touch), so the solver can stop bodies before they meet. Body a is always a
// sphere; contacts come sorted by (a, b) on every backend. Scratch storage is
// kept between steps.
template <class Device, class T = float>
class CollisionDetection {
 public:
  using View = typename Bodies<Device, T>::View;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;

  // Fills `contacts` (friction coefficient mu for models with friction) and
  // returns their number.
  template <class Model>
  std::size_t detect(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, T margin, T mu = T(0),
                     stream_t stream = stream_t{}) {
    if (!(margin >= 0)) throw InvalidArgumentError("gpusolve: CollisionDetection: margin must be >= 0");
    const View b = bodies.view();
    const std::size_t n = b.size();
    contacts.resize(0);
    if (n == 0) return 0;
    const auto policy = detail::thrust_policy(Device{}, stream);
    const std::size_t pair_count = grid_.find_pairs(bodies, margin, stream);

    detail::ensure_size(obstacles_, n);
    detail::ensure_size(pair_start_, n + 1);
    detail::ensure_size(count_, n);
    detail::ensure_size(offset_, n);
    const thrust::counting_iterator<std::uint32_t> first(0);
    const std::uint32_t obstacle_count = std::uint32_t(
        thrust::copy_if(policy, first, first + n, obstacles_.data(), detail::IsObstacle<View>{b}) -
        obstacles_.data());
    const auto keys = thrust::make_transform_iterator(first, detail::FirstKeyOf{});
    thrust::lower_bound(policy, grid_.pairs(), grid_.pairs() + pair_count, keys, keys + (n + 1),
                        pair_start_.data());

    using Walk = detail::ContactWalk<View, T>;
    const Walk walk{b, margin, grid_.pairs(), pair_start_.data(), obstacles_.data(), obstacle_count};
    launch(Device{}, n, detail::CountContacts<Walk>{walk, count_.data()}, stream);
    thrust::inclusive_scan(policy, count_.data(), count_.data() + n, offset_.data());
    const std::size_t total = detail::read_back<Device>(offset_.data(), n - 1, stream);
    contacts.resize(total);
    using CView = typename Contacts<Device, T, Model>::View;
    launch(Device{}, n, detail::WriteContacts<Walk, CView, T>{walk, offset_.data(), count_.data(), contacts.view(), mu},
           stream);
    return total;
  }

  const UniformGrid<Device, T>& grid() const { return grid_; }

 private:
  UniformGrid<Device, T> grid_;
  D1<std::uint32_t> obstacles_, pair_start_, count_, offset_;
};

}  // namespace gpusolve::rbd
