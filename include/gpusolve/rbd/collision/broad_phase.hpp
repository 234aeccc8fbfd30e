// Broad phase: a uniform hashed grid over the spheres, built with Thrust sorts,
// searches and scans; the same code on both backends.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <thrust/binary_search.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>
#include <thrust/transform_reduce.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/detail/scratch.hpp"
#include "gpusolve/rbd/detail/thrust_backend.hpp"

namespace gpusolve::rbd {

// A sphere pair (a, b), a < b, as one sortable key: a in the high 32 bits.
GPUSOLVE_HD inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(a) << 32) | b;
}
GPUSOLVE_HD inline std::uint32_t pair_a(std::uint64_t k) { return std::uint32_t(k >> 32); }
GPUSOLVE_HD inline std::uint32_t pair_b(std::uint64_t k) { return std::uint32_t(k & 0xffffffffu); }

namespace detail {

// Bodies on the grid: spheres that are not removed.
template <class View>
GPUSOLVE_HD bool on_grid(const View& b, std::size_t i) {
  return b.shape[i] == sphere && b.status[i] != removed;
}

// Two grid spheres whose surfaces are closer than `margin`.
template <class View, class T>
GPUSOLVE_HD bool spheres_near(const View& b, std::size_t i, std::size_t j, T margin) {
  T d2 = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const T d = b.pos(i, c) - b.pos(j, c);
    d2 += d * d;
  }
  const T reach = b.radius[i] + b.radius[j] + margin;
  return d2 < reach * reach;
}

template <class View, class T>
struct SphereReach {  // diameter plus margin: the smallest admissible cell size
  View b;
  T margin;
  GPUSOLVE_HD T operator()(std::size_t i) const { return on_grid(b, i) ? 2 * b.radius[i] + margin : T(0); }
};

// The grid: cell (x, y, z) = floor(pos / cell), hashed into `buckets` (a power of two).
template <class T>
struct GridGeometry {
  T inv_cell;
  std::uint32_t mask;
  GPUSOLVE_HD std::int32_t coord(T x) const { return std::int32_t(std::floor(x * inv_cell)); }
  GPUSOLVE_HD std::uint32_t hash(std::int32_t x, std::int32_t y, std::int32_t z) const {
    return ((std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (std::uint32_t(z) * 83492791u)) &
           mask;
  }
};

template <class View, class T>
struct HashSpheres {
  View b;
  GridGeometry<T> g;
  std::uint32_t* hash;
  std::uint32_t* index;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    index[i] = std::uint32_t(i);
    hash[i] = on_grid(b, i) ? g.hash(g.coord(b.pos(i, 0)), g.coord(b.pos(i, 1)), g.coord(b.pos(i, 2)))
                            : g.mask + 1;  // past every bucket: sorts last, never searched
  }
};

// Visits every grid sphere j > i near sphere i, in the 27 cells around i's. A
// bucket two neighbour cells hash to is visited once; spheres that share a
// bucket only by a hash collision fail the distance test.
template <class View, class T>
struct NeighbourWalk {
  View b;
  GridGeometry<T> g;
  T margin;
  const std::uint32_t* index;  // body indices sorted by bucket
  const std::uint32_t* start;  // first entry of each bucket in `index`
  const std::uint32_t* end;    // one past its last entry

  template <class F>
  GPUSOLVE_HD void operator()(std::size_t i, F&& visit) const {
    if (!on_grid(b, i)) return;
    const std::int32_t x = g.coord(b.pos(i, 0)), y = g.coord(b.pos(i, 1)), z = g.coord(b.pos(i, 2));
    std::uint32_t seen[27];
    int nseen = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::uint32_t h = g.hash(x + dx, y + dy, z + dz);
          bool dup = false;
          for (int s = 0; s < nseen; ++s) dup = dup || seen[s] == h;
          if (dup) continue;
          seen[nseen++] = h;
          for (std::uint32_t s = start[h]; s < end[h]; ++s) {
            const std::uint32_t j = index[s];
            if (j > i && spheres_near(b, i, j, margin)) visit(j);
          }
        }
  }
};

template <class Walk>
struct CountPairs {
  Walk walk;
  std::uint32_t* count;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t c = 0;
    walk(i, [&c](std::uint32_t) { ++c; });
    count[i] = c;
  }
};

template <class Walk>
struct WritePairs {
  Walk walk;
  const std::uint32_t* offset;  // inclusive scan of the counts
  const std::uint32_t* count;
  std::uint64_t* pairs;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t o = offset[i] - count[i];
    walk(i, [&](std::uint32_t j) { pairs[o++] = pair_key(std::uint32_t(i), j); });
  }
};

}  // namespace detail

// Finds every pair of spheres (not removed) whose surfaces are closer than a
// margin, on the backend of the bodies. The cell size is the largest sphere
// diameter plus the margin, so near spheres always sit in neighbouring cells.
// Scratch storage is kept and reused from step to step.
template <class Device, class T = float>
class UniformGrid {
 public:
  using View = typename Bodies<Device, T>::View;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;

  // Rebuilds the grid and the pair list; returns the number of pairs. The pairs
  // are sorted by (a, b), a < b: pair_key order.
  std::size_t find_pairs(Bodies<Device, T>& bodies, T margin, stream_t stream = stream_t{}) {
    const View b = bodies.view();
    const std::size_t n = b.size();
    count_ = 0;
    if (n == 0) return 0;
    const auto policy = detail::thrust_policy(Device{}, stream);
    const T cell = thrust::transform_reduce(policy, thrust::counting_iterator<std::size_t>(0),
                                            thrust::counting_iterator<std::size_t>(n),
                                            detail::SphereReach<View, T>{b, margin}, T(0), thrust::maximum<T>());
    if (!(cell > 0)) return 0;  // no spheres
    if (!std::isfinite(cell))
      throw InvalidArgumentError("gpusolve: UniformGrid: a sphere radius or the margin is not finite");
    std::uint32_t buckets = 1;
    while (buckets < 2 * n && buckets < (1u << 30)) buckets <<= 1;
    const detail::GridGeometry<T> g{T(1) / cell, buckets - 1};

    detail::ensure_size(hash_, n);
    detail::ensure_size(index_, n);
    detail::ensure_size(count_per_body_, n);
    detail::ensure_size(offset_, n);
    detail::ensure_size(start_, buckets);
    detail::ensure_size(end_, buckets);
    std::uint32_t *hash = hash_.data(), *index = index_.data();
    launch(Device{}, n, detail::HashSpheres<View, T>{b, g, hash, index}, stream);
    // Stable, so bodies in one bucket stay in index order on every backend.
    thrust::stable_sort_by_key(policy, hash, hash + n, index);
    thrust::lower_bound(policy, hash, hash + n, thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(buckets), start_.data());
    thrust::upper_bound(policy, hash, hash + n, thrust::counting_iterator<std::uint32_t>(0),
                        thrust::counting_iterator<std::uint32_t>(buckets), end_.data());

    using Walk = detail::NeighbourWalk<View, T>;
    const Walk walk{b, g, margin, index, start_.data(), end_.data()};
    launch(Device{}, n, detail::CountPairs<Walk>{walk, count_per_body_.data()}, stream);
    thrust::inclusive_scan(policy, count_per_body_.data(), count_per_body_.data() + n, offset_.data());
    count_ = detail::read_back<Device>(offset_.data(), n - 1, stream);
    detail::ensure_size(pairs_, count_);
    launch(Device{}, n, detail::WritePairs<Walk>{walk, offset_.data(), count_per_body_.data(), pairs_.data()},
           stream);
    thrust::sort(policy, pairs_.data(), pairs_.data() + count_);
    return count_;
  }

  // The pairs of the last find_pairs: count() keys in pair_key order, in the
  // bodies' memory.
  const std::uint64_t* pairs() const { return pairs_.data(); }
  std::size_t count() const { return count_; }

 private:
  D1<std::uint32_t> hash_, index_, count_per_body_, offset_, start_, end_;
  D1<std::uint64_t> pairs_;
  std::size_t count_ = 0;
};

}  // namespace gpusolve::rbd
