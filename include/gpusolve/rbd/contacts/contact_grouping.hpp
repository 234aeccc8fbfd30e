// ContactGrouping: the two body entries of every contact sorted by body (thesis
// 5.2's update-cache layout), rebuilt on the backend once per step.
#pragma once

#include <cstddef>
#include <cstdint>

#include <thrust/binary_search.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/sort.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"
#include "gpusolve/rbd/detail/scratch.hpp"
#include "gpusolve/rbd/detail/thrust_backend.hpp"

namespace gpusolve::rbd {

namespace detail {

// Kernels of ContactGrouping::build (namespace scope: nvcc rejects private
// nested types as kernel template arguments).
template <class BV, class CV, class U32View>
struct GroupKeys {
  BV b;
  CV c;
  U32View key, sorted;
  GPUSOLVE_HD void operator()(std::size_t e) const {
    const std::uint32_t k = (e & 1) ? c.b[e / 2] : c.a[e / 2];
    key[e] = b.moving(k) ? k : static_cast<std::uint32_t>(b.size());
    sorted[e] = static_cast<std::uint32_t>(e);
  }
};
template <class U32View>
struct GroupRanks {
  U32View key, sorted, start, slot, rank;
  std::size_t bodies;
  GPUSOLVE_HD void operator()(std::size_t p) const {
    slot[sorted[p]] = static_cast<std::uint32_t>(p);
    rank[p] = key[p] < bodies ? static_cast<std::uint32_t>(p - start[key[p]]) : 0u;
  }
};
template <class U32View>
struct SegmentLength {
  U32View start;
  GPUSOLVE_HD std::uint32_t operator()(std::size_t k) const { return start[k + 1] - start[k]; }
};

}  // namespace detail

// Entry e = 2i + s is side s (0: body a, 1: body b) of contact i. After build(),
// the entries of each moving body occupy one segment [start[k], start[k+1]) of
// the sorted order; slot[e] is e's position there and rank[p] the position's
// offset from its segment's first entry (the thesis's reductionCount). Entries
// of fixed bodies sort behind every segment: they receive no velocity update.
template <class Device>
class ContactGrouping {
 public:
  using U32 = VectorD1<std::uint32_t, device_is<Device>>;
  using U32View = decltype(std::declval<U32&>().view());

  struct View {
    U32View slot;   // 2 * contacts: sorted position of each entry
    U32View rank;   // 2 * contacts: offset of a sorted position within its body's segment
    U32View start;  // bodies + 1: first sorted position of each body's segment
    U32View entry;  // 2 * contacts: the entry at each sorted position (contact = entry / 2)
    std::size_t bodies;
  };

  // Groups the contacts of `c` over the bodies of `b` (their views). One wait
  // for the device: the largest segment decides the number of reduction passes.
  template <class BV, class CV>
  void build(const BV& b, const CV& c, stream_t stream = stream_t{}) {
    const std::size_t entries = 2 * c.size(), nb = b.size();
    for (U32* v : {&key_, &sorted_, &slot_, &rank_}) detail::ensure_size(*v, entries);
    detail::ensure_size(start_, nb + 1);
    bodies_ = nb;
    const Device dev{};
    launch(dev, entries, detail::GroupKeys<BV, CV, U32View>{b, c, key_.view(), sorted_.view()}, stream);
    const auto policy = detail::thrust_policy(dev, stream);
    thrust::stable_sort_by_key(policy, key_.data(), key_.data() + entries, sorted_.data());
    const thrust::counting_iterator<std::uint32_t> body(0);
    thrust::lower_bound(policy, key_.data(), key_.data() + entries, body, body + (nb + 1), start_.data());
    launch(dev, entries,
           detail::GroupRanks<U32View>{key_.view(), sorted_.view(), start_.view(), slot_.view(), rank_.view(), nb},
           stream);
    const auto s = start_.view();
    max_segment_ = max_over(dev, nb, detail::SegmentLength<U32View>{s}, std::uint32_t(0), stream);
  }

  View view() { return View{slot_.view(), rank_.view(), start_.view(), sorted_.view(), bodies_}; }
  // The most contacts any moving body has (the thesis's c_max).
  std::size_t max_segment() const { return max_segment_; }
  // ceil(log2 c_max): passes of the log-step segmented reduction (Listing 12).
  std::size_t passes() const {
    std::size_t s = 0;
    while ((std::size_t(1) << s) < max_segment_) ++s;
    return s;
  }

 private:
  U32 key_, sorted_, slot_, rank_, start_;
  std::size_t bodies_ = 0, max_segment_ = 0;
};

}  // namespace gpusolve::rbd
