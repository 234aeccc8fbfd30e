// ContactGrouping: the two body entries of every contact sorted by body (thesis
// 5.2's update-cache layout), rebuilt on the backend once per step.
#pragma once

#include <cstddef>
#include <cstdint>

#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/detail/device_algorithms.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"
#include "gpusolve/rbd/detail/scratch.hpp"

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
// start[k] = the first sorted position whose key is at least k.
struct SegmentStarts {
  const std::uint32_t* key;  // sorted
  std::size_t entries;
  std::uint32_t* start;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    start[k] = std::uint32_t(thrust::lower_bound(thrust::seq, key, key + entries, std::uint32_t(k)) - key);
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

  // Groups the contacts of `c` over the bodies of `b` (their views): queued on
  // `stream`, without a host wait or an allocation once warm.
  template <class BV, class CV>
  void build(const BV& b, const CV& c, stream_t stream = stream_t{}) {
    const std::size_t entries = 2 * c.size(), nb = b.size();
    for (U32* v : {&key_, &entry_, &sorted_key_, &sorted_, &slot_, &rank_}) detail::ensure_size(*v, entries);
    detail::ensure_size(start_, nb + 1);
    bodies_ = nb;
    max_segment_known_ = false;
    int bits = 1;
    while ((std::size_t(1) << bits) <= nb) ++bits;  // keys 0 ... nb
    const Device dev{};
    launch(dev, entries, detail::GroupKeys<BV, CV, U32View>{b, c, key_.view(), entry_.view()}, stream);
    algorithms_.sort_pairs(key_.data(), sorted_key_.data(), entry_.data(), sorted_.data(), entries, bits, stream);
    launch(dev, nb + 1, detail::SegmentStarts{sorted_key_.data(), entries, start_.data()}, stream);
    launch(dev, entries,
           detail::GroupRanks<U32View>{sorted_key_.view(), sorted_.view(), start_.view(), slot_.view(), rank_.view(), nb},
           stream);
    stream_ = stream;
  }

  View view() { return View{slot_.view(), rank_.view(), start_.view(), sorted_.view(), bodies_}; }
  // The most contacts any moving body has (the thesis's c_max); the first call
  // after a build waits for it.
  std::size_t max_segment() {
    if (!max_segment_known_) {
      max_segment_ = max_over(Device{}, bodies_, detail::SegmentLength<U32View>{start_.view()}, std::uint32_t(0), stream_);
      max_segment_known_ = true;
    }
    return max_segment_;
  }
  // ceil(log2 c_max): passes of the log-step segmented reduction (Listing 12).
  std::size_t passes() {
    const std::size_t m = max_segment();
    std::size_t s = 0;
    while ((std::size_t(1) << s) < m) ++s;
    return s;
  }

 private:
  U32 key_, entry_, sorted_key_, sorted_, slot_, rank_, start_;
  detail::DeviceAlgorithms<Device> algorithms_;
  stream_t stream_{};
  std::size_t bodies_ = 0, max_segment_ = 0;
  bool max_segment_known_ = false;
};

}  // namespace gpusolve::rbd
