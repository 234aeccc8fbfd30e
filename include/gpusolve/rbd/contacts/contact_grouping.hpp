// ContactGrouping: the two body entries of every contact sorted by body (thesis
// 5.2's update-cache layout), rebuilt on the backend once per step.
#pragma once

#include <cstddef>
#include <cstdint>

#include <cuda/atomic>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/container/ensure_size.hpp"

namespace gpusolve::rbd {

namespace detail {

// Kernels of ContactGrouping::build (namespace scope: nvcc rejects private
// nested types as kernel template arguments): a counting sort by body. Entries
// arrive in their segment in any order (an atomic counter); each then finds its
// rank among the segment's entries by counting those with a smaller index, so
// the order is the entries' order on every run and backend. (A radix sort's
// passes cost several microseconds each at any size; these passes are short.)
template <class BV, class CV, class U32View>
struct GroupKeys {  // key[e], arrival[e] within its key's segment; start[0] = 0
  BV b;
  CV c;
  U32View key, arrival, count, start;
  GPUSOLVE_HD void operator()(std::size_t e) const {
    if (e == 0) start[0] = 0;
    const std::uint32_t k = (e & 1) ? c.b[e / 2] : c.a[e / 2];
    const std::uint32_t g = b.moving(k) ? k : static_cast<std::uint32_t>(b.size());
    key[e] = g;
    arrival[e] = cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(count[g]).fetch_add(
        1u, cuda::std::memory_order_relaxed);
  }
};
template <class U32View>
struct GroupArrive {  // arrived[start[key[e]] + arrival[e]] = e
  U32View key, arrival, start, arrived;
  GPUSOLVE_HD void operator()(std::size_t e) const { arrived[start[key[e]] + arrival[e]] = std::uint32_t(e); }
};
// Entries of fixed bodies keep their arrival order: no update reads them.
template <class U32View>
struct GroupRanks {
  U32View key, arrival, start, arrived, sorted, slot, rank;
  std::size_t bodies;
  GPUSOLVE_HD void operator()(std::size_t e) const {
    const std::uint32_t k = key[e], first = start[k];
    std::uint32_t r = arrival[e];
    if (k < bodies) {
      r = 0;
      for (std::uint32_t q = first, end = start[k + 1]; q < end; ++q) r += arrived[q] < e;
    }
    const std::uint32_t p = first + r;
    sorted[p] = std::uint32_t(e);
    slot[e] = p;
    rank[p] = k < bodies ? r : 0u;
  }
};
template <class U32View>
struct ZeroU32 {
  U32View v;
  GPUSOLVE_HD void operator()(std::size_t i) const { v[i] = 0u; }
};

// The build as a program (execution/persistent_loop.hpp's contract, with
// e.scan): the same phases as launches, or between a persistent kernel's
// barriers. Ends with e.sync(). The entries are counted where the phases run
// (the contacts' count may be known only to the device).
template <class BV, class CV, class U32View>
struct GroupingBuild {
  GroupKeys<BV, CV, U32View> keys;
  GroupArrive<U32View> arrive;
  GroupRanks<U32View> ranks;
  U32View count;
  std::size_t bodies;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    const std::size_t entries = 2 * keys.c.size();
    if (entries == 0) {
      e.each(bodies + 2, ZeroU32<U32View>{ranks.start});
      e.sync();
      return;
    }
    e.each(bodies + 1, ZeroU32<U32View>{count});
    e.sync();
    e.each(entries, keys);
    e.sync();
    e.scan(count.data(), ranks.start.data() + 1, bodies + 1);
    e.sync();
    e.each(entries, arrive);
    e.sync();
    e.each(entries, ranks);
    e.sync();
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
// of fixed bodies come behind every segment, in no set order: they receive no
// velocity update.
template <class Device>
class ContactGrouping {
 public:
  using U32 = VectorD1<std::uint32_t, device_is<Device>>;
  using U32View = decltype(std::declval<U32&>().view());

  struct View {
    U32View slot;   // 2 * contacts: sorted position of each entry
    U32View rank;   // 2 * contacts: offset of a sorted position within its body's segment
    U32View start;  // bodies + 1 (and the fixed bodies' end): first sorted position of each body's segment
    U32View entry;  // 2 * contacts: the entry at each sorted position (contact = entry / 2)
    std::size_t bodies;
  };

  // Groups the contacts of `c` over the bodies of `b` (their views): queued on
  // `stream`, without a host wait or an allocation once warm.
  template <class BV, class CV>
  void build(const BV& b, const CV& c, stream_t stream = stream_t{}) {
    program(b, c, stream)(detail::LaunchExec<Device, std::uint32_t>{stream, &algorithms_});
  }
  // build() as a program whose phases the caller runs (a solver's persistent
  // kernel); storage is sized here, on the host.
  template <class BV, class CV>
  detail::GroupingBuild<BV, CV, U32View> program(const BV& b, const CV& c, stream_t stream = stream_t{}) {
    const std::size_t entries = 2 * c.bound(), nb = b.size();
    for (U32* v : {&key_, &arrival_, &arrived_, &sorted_, &slot_, &rank_}) gpusolve::detail::ensure_size(*v, entries);
    gpusolve::detail::ensure_size(count_, nb + 1);  // keys 0 ... nb: nb gathers the fixed bodies' entries
    gpusolve::detail::ensure_size(start_, nb + 2);
    bodies_ = nb;
    max_segment_known_ = false;
    stream_ = stream;
    return {{b, c, key_.view(), arrival_.view(), count_.view(), start_.view()},
            {key_.view(), arrival_.view(), start_.view(), arrived_.view()},
            {key_.view(), arrival_.view(), start_.view(), arrived_.view(), sorted_.view(), slot_.view(), rank_.view(), nb},
            count_.view(),
            nb};
  }

  View view() { return View{slot_.view(), rank_.view(), start_.view(), sorted_.view(), bodies_}; }
  // The most contacts any moving body has (the thesis's c_max); the first call
  // after a build waits for it.
  std::size_t max_segment() {
    if (!max_segment_known_) {
      if (max_segment_out_.size_x() == 0) max_segment_out_.resize(1);
      algorithms_.reduce_into(bodies_, detail::SegmentLength<U32View>{start_.view()}, std::uint32_t(0), detail::MaxOp{},
                              max_segment_out_.data(), stream_);
      max_segment_ = detail::read_back<Device>(max_segment_out_.data(), 0, stream_);
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
  U32 key_, arrival_, arrived_, sorted_, slot_, rank_, count_, start_, max_segment_out_;
  detail::DeviceAlgorithms<Device> algorithms_;
  stream_t stream_{};
  std::size_t bodies_ = 0, max_segment_ = 0;
  bool max_segment_known_ = false;
};

}  // namespace gpusolve::rbd
