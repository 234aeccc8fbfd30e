// Broad phase: a uniform hashed grid over the bodies' bounding spheres, sized
// by the moving bodies, built by counting the bodies of each bucket and a
// scan, queued on a stream (no host wait); the same kernels on both backends.
// Fixed bodies too large for its cells, and planes, are the obstacles that
// collision detection tests against every moving body.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include <limits>

#include <cuda/atomic>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/execution/backend.hpp"

namespace gpusolve::rbd {

// A body pair (a, b) as one sortable key: a in the high 32 bits.
GPUSOLVE_HD inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return (std::uint64_t(a) << 32) | b;
}
GPUSOLVE_HD inline std::uint32_t pair_a(std::uint64_t k) { return std::uint32_t(k >> 32); }
GPUSOLVE_HD inline std::uint32_t pair_b(std::uint64_t k) { return std::uint32_t(k & 0xffffffffu); }

namespace detail {

// Bodies that may go on the grid: not removed, not a plane, at a finite
// position (a NaN or infinity cannot be placed in a cell; detection reports the body).
template <class View>
GPUSOLVE_HD bool grid_candidate(const View& b, std::size_t i) {
  if (b.shape[i] == plane || b.status[i] == removed) return false;
  for (std::size_t c = 0; c < 3; ++c)
    if (!(b.pos(i, c) - b.pos(i, c) == 0)) return false;  // NaN and inf give NaN
  return true;
}

// A body's bounding diameter plus the margin: the smallest cell that holds it.
template <class View, class T>
GPUSOLVE_HD T reach_of(const View& b, std::size_t i, T margin) {
  return 2 * b.radius[i] + margin;
}

// A sphere's centre and radius (another body's bounding sphere), copied in the
// grid's sorted order so that a walk reads a neighbour in one load, without
// its body index first.
template <class T>
struct alignas(4 * sizeof(T)) GridSphere {
  T x[3], r;
};

// Two spheres whose surfaces are closer than `margin`.
template <class T>
GPUSOLVE_HD bool spheres_near(const GridSphere<T>& a, const GridSphere<T>& b, T margin) {
  T d2 = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const T d = a.x[c] - b.x[c];
    d2 += d * d;
  }
  const T reach = a.r + b.r + margin;
  return d2 < reach * reach;
}

template <class View, class T>
GPUSOLVE_HD GridSphere<T> grid_sphere(const View& b, std::size_t i) {
  return {{b.pos(i, 0), b.pos(i, 1), b.pos(i, 2)}, b.radius[i]};
}

// The reach of a moving body on the grid (0 for any other): the cell size is
// their maximum; +inf when not finite.
template <class View, class T>
struct BodyReach {
  View b;
  T margin;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    if (!moves(b.status[i]) || !grid_candidate(b, i)) return T(0);
    const T reach = reach_of(b, i, margin);
    return reach <= std::numeric_limits<T>::max() ? reach : std::numeric_limits<T>::infinity();
  }
};

// The grid: cell (x, y, z) = floor(pos / cell), hashed into `buckets` (a power
// of two). The cell size is read in the kernel from the backend's memory, where
// the reduction left it, so the host never waits for it; a cell that is not a
// positive finite size (nothing moves, or a radius that is not finite) leaves
// every body off the grid.
template <class T>
struct GridGeometry {
  T cell, inv_cell;
  std::uint32_t mask;
  bool valid;
  GPUSOLVE_HD GridGeometry(const T* cell_size, std::uint32_t bucket_mask)
      : cell(*cell_size), inv_cell(0), mask(bucket_mask), valid(cell > T(0) && cell <= std::numeric_limits<T>::max()) {
    if (valid) inv_cell = T(1) / cell;
  }
  // Body i goes on the grid: a candidate that moves or fits in a cell.
  template <class View>
  GPUSOLVE_HD bool holds(const View& b, std::size_t i, T margin) const {
    return valid && grid_candidate(b, i) && (moves(b.status[i]) || reach_of(b, i, margin) <= cell);
  }
  GPUSOLVE_HD std::int32_t coord(T x) const { return std::int32_t(std::floor(x * inv_cell)); }
  GPUSOLVE_HD std::uint32_t hash(std::int32_t x, std::int32_t y, std::int32_t z) const {
    return ((std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (std::uint32_t(z) * 83492791u)) &
           mask;
  }
};

// A counting sort of the bodies by bucket, in two passes around a scan of the
// counts. A body's rank in its bucket comes from an atomic counter, so the
// order within a bucket differs from run to run; the walks sort what they find,
// so no result depends on it. (A radix sort's passes cost several microseconds
// each at any size; these two passes are short.)
template <class View, class T>
struct BinBodies {  // hash[i], and rank[i] within its bucket; first[0] = 0
  View b;
  const T* cell;
  T margin;
  std::uint32_t mask;
  std::uint32_t *hash, *rank, *count, *first;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const GridGeometry<T> g(cell, mask);
    if (i == 0) first[0] = 0;
    if (!g.holds(b, i, margin)) {
      hash[i] = mask + 1;  // past every bucket: never placed, never walked
      return;
    }
    const std::uint32_t h = g.hash(g.coord(b.pos(i, 0)), g.coord(b.pos(i, 1)), g.coord(b.pos(i, 2)));
    hash[i] = h;
    rank[i] = cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(count[h]).fetch_add(
        1u, cuda::std::memory_order_relaxed);
  }
};

// Bucket h holds entries [first[h], first[h + 1]); body i goes to
// first[hash[i]] + rank[i], with its bounding sphere beside its index.
template <class View, class T>
struct PlaceBodies {
  View b;
  const std::uint32_t *hash, *rank, *first;
  std::uint32_t mask;
  std::uint32_t* index;
  GridSphere<T>* spheres;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const std::uint32_t h = hash[i];
    if (h > mask) return;
    const std::uint32_t p = first[h] + rank[i];
    index[p] = std::uint32_t(i);
    spheres[p] = grid_sphere<View, T>(b, i);
  }
};

// Visits every grid body j > i whose bounding sphere is near body i's, in the
// 27 cells around i's, in bucket order: visit(j, its packed bounding sphere).
// A bucket two neighbour cells hash to is visited once; bodies that share a
// bucket only by a hash collision fail the distance test.
// A walk is a chain of dependent loads: the 27 buckets' ranges are loaded
// together, then a cell's entries in batches of `batch` (an entry's index
// and sphere, read-only here, loaded before the first of the batch is
// visited), so that a walk waits once a batch instead of once an entry.
template <class View, class T>
struct NeighbourWalk {
  static constexpr int batch = 4;

  View b;
  const T* cell;
  std::uint32_t mask;
  T margin;
  const std::uint32_t* index;    // body indices sorted by bucket
  const GridSphere<T>* spheres;  // their spheres, in that order
  const std::uint32_t* bucket;   // bucket h: entries [bucket[h], bucket[h + 1]) of `index`

  template <class F>
  GPUSOLVE_HD void operator()(std::size_t i, F&& visit) const {
    const GridGeometry<T> g(cell, mask);
    if (!g.holds(b, i, margin)) return;
    const GridSphere<T> me = grid_sphere<View, T>(b, i);
    const std::int32_t x = g.coord(me.x[0]), y = g.coord(me.x[1]), z = g.coord(me.x[2]);
    // Cell c = 9 (dz + 1) + 3 (dy + 1) + dx + 1; bit c of dup: an earlier cell has its bucket.
    std::uint32_t h[27], dup = 0;
    GPUSOLVE_UNROLL
    for (int c = 0; c < 27; ++c) {
      h[c] = g.hash(x + c % 3 - 1, y + c / 3 % 3 - 1, z + c / 9 - 1);
      GPUSOLVE_UNROLL
      for (int d = 0; d < c; ++d) dup |= std::uint32_t(h[d] == h[c]) << c;
    }
    std::uint32_t first[27], last[27];
    GPUSOLVE_UNROLL
    for (int c = 0; c < 27; ++c) first[c] = bucket[h[c]], last[c] = bucket[h[c] + 1];  // no branch between the loads
    for (int c = 0; c < 27; ++c) {
      if ((dup >> c) & 1u) continue;
      for (std::uint32_t s = first[c]; s < last[c]; s += batch) {
        std::uint32_t j[batch];
        GridSphere<T> other[batch];
        GPUSOLVE_UNROLL
        for (int q = 0; q < batch; ++q)
          if (s + q < last[c]) j[q] = index[s + q], other[q] = spheres[s + q];
        GPUSOLVE_UNROLL
        for (int q = 0; q < batch; ++q)
          if (s + q < last[c] && j[q] > i && spheres_near(me, other[q], margin)) visit(j[q], other[q]);
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
    walk(i, [&c](std::uint32_t, const auto&) { ++c; });
    count[i] = c;
  }
};

// Writes body i's pairs at [offset[i] - count[i], offset[i]) and sorts them
// there by b (the walk meets them in bucket order; a body has few), so the
// list comes out in pair_key order without a global sort. A body whose pairs
// would pass `capacity` writes nothing: the caller grows the list and repeats.
template <class Walk>
struct WritePairs {
  Walk walk;
  const std::uint32_t* offset;  // inclusive scan of the counts
  const std::uint32_t* count;
  std::uint64_t* pairs;
  std::size_t capacity;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const std::uint32_t first = offset[i] - count[i], last = offset[i];
    if (last > capacity) return;
    std::uint32_t o = first;
    walk(i, [&](std::uint32_t j, const auto&) { pairs[o++] = pair_key(std::uint32_t(i), j); });
    for (std::uint32_t p = first + 1; p < last; ++p) {  // insertion sort
      const std::uint64_t key = pairs[p];
      std::uint32_t q = p;
      for (; q > first && pairs[q - 1] > key; --q) pairs[q] = pairs[q - 1];
      pairs[q] = key;
    }
  }
};

}  // namespace detail

// Finds every pair of bodies on the grid whose bounding spheres are closer
// than a margin, on the backend of the bodies. The cell size is the largest
// bounding diameter of a moving body plus the margin, so near bodies always
// sit in neighbouring cells; a fixed body larger than that is left off
// (GridGeometry::holds), for the caller to test against every moving body.
// queue_grid() builds the grid for kernels that walk it (collision detection);
// queue() also lists the pairs. Both only queue device work: the pair count stays in the backend's memory
// until a caller reads it; the list has a capacity that grows geometrically
// and is never silently cut (a caller that finds count > capacity grows it
// with reserve() and queues again). Scratch storage is kept and reused.
template <class Device, class T = float>
class UniformGrid {
 public:
  using View = typename Bodies<Device, T>::View;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;

  using Walk = detail::NeighbourWalk<View, T>;

  // Queues the grid's rebuild. Afterwards, in stream order, cell() holds the
  // cell size (+inf when a radius or the margin is not finite) and walk(b,
  // margin) visits each body's near neighbours in kernels (NeighbourWalk).
  // A caller that reduces the bodies itself may pass `cell`, where its
  // reduction leaves BodyReach's maximum in stream order; cell() is then that.
  Walk queue_grid(Bodies<Device, T>& bodies, T margin, stream_t stream = stream_t{}, const T* cell = nullptr) {
    const View b = bodies.view();
    n_ = b.size();
    std::uint32_t buckets = 1;
    while (buckets < 2 * n_ && buckets < (1u << 30)) buckets <<= 1;
    for (D1<std::uint32_t>* v : {&hash_, &rank_, &index_}) gpusolve::detail::ensure_size(*v, n_);
    gpusolve::detail::ensure_size(spheres_, n_);
    gpusolve::detail::ensure_size(bucket_count_, buckets);
    gpusolve::detail::ensure_size(first_, buckets + 1);
    if (cell_.size_x() == 0) cell_.resize(1);
    cell_used_ = cell ? cell : cell_.data();
    const Walk walk{b, cell_used_, buckets - 1, margin, index_.data(), spheres_.data(), first_.data()};
    if (n_ == 0) return walk;
    const Device dev{};
    if (!cell) algorithms_.max_into(n_, detail::BodyReach<View, T>{b, margin}, T(0), cell_.data(), stream);
    bucket_count_.fill(0u, stream);
    launch(dev, n_,
           detail::BinBodies<View, T>{b, cell_used_, margin, buckets - 1, hash_.data(), rank_.data(), bucket_count_.data(),
                                       first_.data()},
           stream);
    algorithms_.inclusive_sum(bucket_count_.data(), first_.data() + 1, buckets, stream);
    launch(dev, n_,
           detail::PlaceBodies<View, T>{b, hash_.data(), rank_.data(), first_.data(), buckets - 1, index_.data(),
                                         spheres_.data()},
           stream);
    return walk;
  }

  // Queues the grid's rebuild and the pair list. Afterwards, in stream order,
  // pair_count() holds the number of pairs and cell() the cell size; when the
  // count is at most capacity(), pairs() lists them sorted by (a, b), a < b:
  // pair_key order, those of body i at [pair_end(i) - pair_count_of(i), pair_end(i)).
  void queue(Bodies<Device, T>& bodies, T margin, stream_t stream = stream_t{}) {
    const Walk walk = queue_grid(bodies, margin, stream);
    if (n_ == 0) return;
    for (D1<std::uint32_t>* v : {&count_, &offset_}) gpusolve::detail::ensure_size(*v, n_);
    if (pairs_.size_x() < 4 * n_) reserve(4 * n_);  // a pile has about 6 per body: at most one regrowth
    const Device dev{};
    launch(dev, n_, detail::CountPairs<Walk>{walk, count_.data()}, stream);
    algorithms_.inclusive_sum(count_.data(), offset_.data(), n_, stream);
    launch(dev, n_, detail::WritePairs<Walk>{walk, offset_.data(), count_.data(), pairs_.data(), pairs_.size_x()},
           stream);
  }

  // queue(), then waits for the count, growing the list and repeating when it
  // was short; returns the number of pairs (the convenience of tests and tools).
  std::size_t find_pairs(Bodies<Device, T>& bodies, T margin, stream_t stream = stream_t{}) {
    for (;;) {
      queue(bodies, margin, stream);
      if (n_ == 0) return count_read_ = 0;
      if (!(detail::read_back<Device>(cell_.data(), 0, stream) <= std::numeric_limits<T>::max()))
        throw InvalidArgumentError("gpusolve: UniformGrid: a body's bounding radius or the margin is not finite");
      count_read_ = detail::read_back<Device>(offset_.data(), n_ - 1, stream);
      if (count_read_ <= capacity()) return count_read_;
      reserve(count_read_);
    }
  }

  // Room for at least `pairs` pairs (grows by half again; contents are lost).
  void reserve(std::size_t pairs) { gpusolve::detail::ensure_size(pairs_, pairs); }
  std::size_t capacity() const { return pairs_.size_x(); }

  // In the backend's memory, valid in stream order after queue():
  const std::uint64_t* pairs() const { return pairs_.data(); }
  const std::uint32_t* pair_end() const { return offset_.data(); }  // per body, inclusive scan of the counts
  const std::uint32_t* pair_count_of() const { return count_.data(); }
  const std::uint32_t* pair_count() const { return n_ ? offset_.data() + (n_ - 1) : nullptr; }
  const T* cell() const { return cell_used_; }
  // The count find_pairs() returned.
  std::size_t count() const { return count_read_; }

 private:
  D1<std::uint32_t> hash_, rank_, index_, bucket_count_, first_, count_, offset_;
  D1<detail::GridSphere<T>> spheres_;
  D1<std::uint64_t> pairs_;
  D1<T> cell_;
  const T* cell_used_ = nullptr;
  detail::DeviceAlgorithms<Device> algorithms_;
  std::size_t n_ = 0, count_read_ = 0;
};

}  // namespace gpusolve::rbd
