// SpatialOrder: an order of a store's bodies along a Morton curve over their
// centres, and the moving of every field of a store into it, so that bodies
// that touch sit near each other in memory and so do the contacts built from
// them (issue 38: once a pile has mixed, the order bodies were added in puts
// a contact's two bodies anywhere).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include <thrust/copy.h>
#include <thrust/gather.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/scatter.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/execution/backend.hpp"

namespace gpusolve::rbd {

namespace detail {

// The 21 low bits of v, spread to every third bit (Morton interleaving).
GPUSOLVE_HD inline std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// The box around a set of centres (empty: low above high).
template <class T>
struct CentreBox {
  T low[3], high[3];
  GPUSOLVE_HD static CentreBox empty() {
    const T big = std::numeric_limits<T>::max();
    return {{big, big, big}, {-big, -big, -big}};
  }
};

// Moving body i's centre as a box of its own; other bodies add nothing.
template <class BV, class T>
struct CentreOf {
  BV b;
  GPUSOLVE_HD CentreBox<T> operator()(std::size_t i) const {
    if (!b.moving(i)) return CentreBox<T>::empty();
    return {{b.pos(i, 0), b.pos(i, 1), b.pos(i, 2)}, {b.pos(i, 0), b.pos(i, 1), b.pos(i, 2)}};
  }
};

template <class T>
struct MergeBoxes {
  GPUSOLVE_HD CentreBox<T> operator()(const CentreBox<T>& x, const CentreBox<T>& y) const {
    CentreBox<T> m;
    for (int k = 0; k < 3; ++k) {
      m.low[k] = x.low[k] < y.low[k] ? x.low[k] : y.low[k];
      m.high[k] = x.high[k] > y.high[k] ? x.high[k] : y.high[k];
    }
    return m;
  }
};

// Body i's place on the curve: its centre's cell in a 2^21-per-axis grid over
// the box of the moving bodies' centres, interleaved; the bodies that do not
// move (fixed, planes, removed) last, in the order they had, so that a
// pair of a moving and a fixed body always has the moving one first.
template <class BV, class T>
struct MortonKey {
  BV b;
  CentreBox<T> box;
  T scale;  // cells per metre
  std::uint64_t* keys;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!b.moving(i)) {
      keys[i] = ~std::uint64_t(0);
      return;
    }
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      T cell = (b.pos(i, k) - box.low[k]) * scale;
      cell = cell > T(0) ? cell : T(0);  // also a NaN centre
      cell = cell < T(0x1fffff) ? cell : T(0x1fffff);
      key |= spread_bits(std::uint64_t(cell)) << k;
    }
    keys[i] = key;
  }
};

}  // namespace detail

// The order: order()[k] is the slot whose body moves to slot k. Sorting is
// stable (bodies in one cell keep their order) and runs on the store's
// backend (thrust's radix sort on the GPU). apply() moves every field of a
// store on any backend, row by row through one scratch row.
template <class Device, class T>
class SpatialOrder {
 public:
  // Computes the order of the bodies of `b`; returns it, in Device's memory.
  const std::uint32_t* compute(Bodies<Device, T>& b, stream_t stream = stream_t{}) {
    const std::size_t n = b.size();
    gpusolve::detail::ensure_size(keys_, n);
    gpusolve::detail::ensure_size(order_, n);
    if (n == 0) return order_.data();
    const auto bv = b.view();
    const auto policy = detail::thrust_policy(Device{}, stream);
    const thrust::counting_iterator<std::size_t> first(0);
    const detail::CentreBox<T> box =
        thrust::transform_reduce(policy, first, first + n, detail::CentreOf<decltype(bv), T>{bv},
                                 detail::CentreBox<T>::empty(), detail::MergeBoxes<T>{});
    T extent = 0;
    for (int k = 0; k < 3; ++k) extent = box.high[k] - box.low[k] > extent ? box.high[k] - box.low[k] : extent;
    const T scale = extent > T(0) ? T(0x1fffff) / extent : T(0);
    launch(Device{}, n, detail::MortonKey<decltype(bv), T>{bv, box, scale, keys_.data()}, stream);
    thrust::sequence(policy, order_.data(), order_.data() + n);
    thrust::stable_sort_by_key(policy, keys_.data(), keys_.data() + n, order_.data());
    return order_.data();
  }

  // Moves body order[k] of `bodies` to slot k, for every field; `order` in
  // the memory of the store's backend D.
  template <class D>
  static void apply(Bodies<D, T>& bodies, const std::uint32_t* order, stream_t stream = stream_t{}) {
    const std::size_t n = bodies.size();
    if (n == 0) return;
    const auto policy = detail::thrust_policy(D{}, stream);
    VectorD1<std::uint8_t, device_is<D>> row8(n);
    VectorD1<std::uint32_t, device_is<D>> row32(n);
    VectorD1<T, device_is<D>> rowT(n);
    const auto scratch = [&](auto* data) {
      using E = std::remove_pointer_t<decltype(data)>;
      if constexpr (std::is_same_v<E, std::uint8_t>) return row8.data();
      else if constexpr (std::is_same_v<E, std::uint32_t>) return row32.data();
      else return rowT.data();
    };
    zip_fields(bodies, bodies, [&](auto& f, auto&, std::size_t rows, bool) {
      std::size_t pitch = 0;
      if constexpr (std::remove_reference_t<decltype(f)>::rank == 2) pitch = f.pitch();
      for (std::size_t r = 0; r < rows; ++r) {
        auto* row = f.data() + r * pitch;
        auto* tmp = scratch(row);
        thrust::gather(policy, order, order + n, row, tmp);
        thrust::copy(policy, tmp, tmp + n, row);
      }
    });
  }

  // inverse[order[k]] = k: where each slot's body went, in Device's memory.
  const std::uint32_t* inverse(std::size_t n, stream_t stream = stream_t{}) {
    gpusolve::detail::ensure_size(inverse_, n);
    if (n == 0) return inverse_.data();
    const auto policy = detail::thrust_policy(Device{}, stream);
    const thrust::counting_iterator<std::uint32_t> first(0);
    thrust::scatter(policy, first, first + n, order_.data(), inverse_.data());
    return inverse_.data();
  }

 private:
  VectorD1<std::uint64_t, device_is<Device>> keys_;
  VectorD1<std::uint32_t, device_is<Device>> order_, inverse_;
};

}  // namespace gpusolve::rbd
