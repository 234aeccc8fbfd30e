// ContactColouring: splits the body pairs in contact in one step into colours,
// sets of pairs that share no moving body, on the contacts' backend.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <cuda/atomic>
#include <thrust/binary_search.h>
#include <thrust/execution_policy.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/contacts/contact_grouping.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"

namespace gpusolve::rbd {

namespace detail {

inline constexpr std::uint32_t uncoloured = 0xffffffffu;
inline constexpr std::uint32_t follows = 0xfffffffeu;  // a pair's later point: it goes with the first
inline constexpr std::uint32_t mask_colours = 64;  // colours chosen first-fit from a 64-bit mask

// A contact's place in the selection order: a hash of its index (so that
// neighbouring contacts rarely wait on each other in long chains), the index
// itself breaking ties. Deterministic: the same contacts give the same colours.
GPUSOLVE_HD inline std::uint64_t colour_key(std::uint32_t i) {
  std::uint32_t h = i * 0x9E3779B1u;
  h ^= h >> 15, h *= 0x85EBCA77u, h ^= h >> 13;
  return (std::uint64_t(h) << 32) | i;
}

// Calls f(j) for every contact j that shares moving body k (contact i's own entry included).
template <class GV, class F>
GPUSOLVE_HD void for_contacts_of(const GV& g, std::uint32_t k, F&& f) {
  for (std::uint32_t p = g.start[k]; p < g.start[k + 1]; ++p) f(g.entry[p] / 2);
}

// Per moving body: the smallest key of its contacts still uncoloured.
template <class BV, class GV>
struct SmallestUncoloured {
  BV b;
  GV g;
  const std::uint32_t* colour;
  std::uint64_t* best;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    if (!b.moving(k)) return;
    std::uint64_t m = ~std::uint64_t(0);
    for_contacts_of(g, std::uint32_t(k), [&](std::uint32_t j) {
      const std::uint64_t key = colour_key(j);
      if (colour[j] == uncoloured && key < m) m = key;
    });
    best[k] = m;
  }
};

// What a colouring's rounds have counted so far, read back in one copy.
struct ColouringCounters {
  std::uint32_t coloured;  // contacts coloured, a pair's later points included
  std::uint32_t colours;   // colours used
  std::uint32_t rounds;    // the last round that coloured a contact, plus one
};

// The start of a build: a pair's first point is to be coloured, its later
// points follow it (counted as coloured at once).
template <class CV>
struct MarkPairs {
  CV c;
  std::uint32_t* colour;
  ColouringCounters* counters;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const bool first = c.opens_pair(i);
    colour[i] = first ? uncoloured : follows;
    if (!first)
      cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(counters->coloured)
          .fetch_add(1, cuda::std::memory_order_relaxed);
  }
};

// An uncoloured contact that is the smallest at each of its moving bodies takes
// the smallest colour none of its neighbours has. Contacts picked in one round
// share no moving body, so none reads a colour another writes in this round.
// Past 64 colours a contact takes 64 + round, distinct from every other round.
template <class BV, class CV, class GV>
struct PickColour {
  BV b;
  CV c;
  GV g;
  std::uint32_t* colour;
  const std::uint64_t* best;
  std::uint32_t round;
  ColouringCounters* counters;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (colour[i] != uncoloured) return;
    const std::uint32_t ends[2] = {c.a[i], c.b[i]};
    const std::uint64_t key = colour_key(std::uint32_t(i));
    for (std::uint32_t k : ends)
      if (b.moving(k) && best[k] != key) return;
    std::uint64_t used = 0;
    for (std::uint32_t k : ends)
      if (b.moving(k))
        for_contacts_of(g, k, [&](std::uint32_t j) {
          if (colour[j] < mask_colours) used |= std::uint64_t(1) << colour[j];
        });
    std::uint32_t pick = 0;
    while (pick < mask_colours && (used >> pick) & 1u) ++pick;
    if (pick == mask_colours) pick = mask_colours + round;
    colour[i] = pick;
    using Counter = cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>;
    Counter(counters->coloured).fetch_add(1, cuda::std::memory_order_relaxed);
    Counter(counters->colours).fetch_max(pick + 1, cuda::std::memory_order_relaxed);
    Counter(counters->rounds).fetch_max(round + 1, cuda::std::memory_order_relaxed);
  }
};

// What a colouring depends on at contact i: its bodies, each with its top bit
// set where the body moves (a build keeps them, the next compares them).
template <class BV>
GPUSOLVE_HD std::uint32_t body_and_motion(const BV& b, std::uint32_t k) {
  return b.moving(k) ? k | 0x80000000u : k;
}
template <class BV, class CV>
struct KeepPairs {
  BV b;
  CV c;
  std::uint32_t *kept_a, *kept_b;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    kept_a[i] = body_and_motion(b, c.a[i]), kept_b[i] = body_and_motion(b, c.b[i]);
  }
};
// Sets *changed where contact i's ends differ from those a build kept.
template <class BV, class CV>
struct ComparePairs {
  BV b;
  CV c;
  const std::uint32_t *kept_a, *kept_b;
  std::uint32_t* changed;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (kept_a[i] != body_and_motion(b, c.a[i]) || kept_b[i] != body_and_motion(b, c.b[i]))
      cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(*changed).store(1u, cuda::std::memory_order_relaxed);
  }
};

struct Sequence {
  std::uint32_t* out;
  GPUSOLVE_HD void operator()(std::size_t i) const { out[i] = std::uint32_t(i); }
};
// bounds[k]: the first place in the sorted colours `sorted` (n of them) holding k or more.
struct ColourBounds {
  const std::uint32_t* sorted;
  std::size_t n;
  std::uint32_t* bounds;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    bounds[k] = std::uint32_t(thrust::lower_bound(thrust::seq, sorted, sorted + n, std::uint32_t(k)) - sorted);
  }
};

// The colours of one build (ContactColouring::view()): colour k's pairs are
// those whose first points are order[bounds[k]], ..., order[bounds[k + 1] - 1],
// with `bounds` in the contacts' backend memory; `widest`: the most pairs of
// one colour.
struct ColourView {
  const std::uint32_t* order;
  const std::uint32_t* bounds;
  std::size_t colours, widest;
};

// f(first, end) for the points [first, end) of the j-th pair of colour k,
// where colour k has one: one thread takes a pair's points.
template <class F, class CV>
struct InColour {
  F f;
  CV c;
  ColourView colours;
  std::size_t k;
  GPUSOLVE_HD void operator()(std::size_t j) const {
    const std::size_t first = colours.bounds[k];
    if (first + j >= colours.bounds[k + 1]) return;
    const std::uint32_t i = colours.order[first + j], a = c.a[i], b = c.b[i];
    const std::size_t n = c.size();
    std::size_t end = i + 1;
    // a and b held, not same_pair(i, end), which loads them again each time (+10 instructions, sm_90)
    while (end < n && c.a[end] == a && c.b[end] == b) ++end;
    f(std::size_t(i), end);
  }
};

// Queues f over the contacts of each colour, colour by colour, through a
// program's executor e (persistent_loop.hpp), a barrier after each colour.
GPUSOLVE_EXEC_CHECK_DISABLE
template <class E, class CV, class F>
GPUSOLVE_HD void sweep_colours(const E& e, const CV& c, const ColourView& colours, const F& f) {
  for (std::size_t k = 0; k < colours.colours; ++k) {
    e.each(colours.widest, InColour<F, CV>{f, c, colours, k});
    e.sync();
  }
}

}  // namespace detail

// Colours the body pairs in contact in `c` (over the bodies of `b`) so that no
// two pairs of one colour share a moving body; pairs with fixed bodies (the
// floor) do not conflict there. A pair is coloured as its first point, and its
// other points (a box face's four) go with it: a sweep takes them one after
// the other in one thread, as PhysX batches a pair's constraints, so a resting
// box costs one colour per neighbour, not one per point (the 20-layer pyramid's
// 29 colours were points: four per box pair). A Jones-Plassmann-style parallel
// greedy colouring: each round, every pair that precedes its uncoloured
// neighbours in a hashed order takes the smallest colour its neighbours leave
// free. About as many colours as the most pairs on one body (a close-packed
// sphere: 12). Deterministic on both backends. After build(), order() lists the
// pairs' first points colour by colour, colour k occupying [offset(k),
// offset(k + 1)), and the later points behind them; those offsets are the
// host's, read back once per build. Past 64 colours a colour number may stay
// empty (see PickColour). Where the contacts join the same bodies in the same
// order as at the last build, none of them having started or stopped moving (a
// structure at rest), the build keeps its colours: one comparison and one read-back.
template <class Device>
class ContactColouring {
 public:
  using U32 = VectorD1<std::uint32_t, device_is<Device>>;

  template <class BV, class CV>
  void build(const BV& b, const CV& c, stream_t stream = stream_t{}) {
    const std::size_t nc = c.size();
    kept_ = nc != 0 && same_pairs(b, c, stream);
    if (kept_) return;
    kept_count_ = 0;
    offsets_.assign(1, 0);
    if (nc == 0) return;
    const std::uint32_t colours = colour(b, c, stream);
    sort_by_colour(nc, colours, stream);
    keep_pairs(b, c, stream);
  }

  std::size_t colours() const { return offsets_.size() - 1; }
  // The colours for a program's sweep (detail::sweep_colours).
  detail::ColourView view() const {
    std::size_t widest = 0;
    for (std::size_t k = 0; k < colours(); ++k) widest = std::max(widest, offsets_[k + 1] - offsets_[k]);
    return {order_.data(), bounds_.data(), colours(), widest};
  }
  std::size_t offset(std::size_t k) const { return offsets_[k]; }
  const std::uint32_t* order() const { return order_.data(); }
  const std::uint32_t* colour() const { return colour_.data(); }
  // The rounds the last build ran, and those it needed (the last that coloured a contact).
  std::size_t rounds() const { return rounds_; }
  std::size_t rounds_needed() const { return needed_; }
  // Whether the last build kept the colours of the one before.
  bool kept() const { return kept_; }

 private:
  // Whether the contacts in `c` join the bodies of the last build's, in its
  // order, with the same bodies moving (bodies numbered past 2^31 are never compared).
  template <class BV, class CV>
  bool same_pairs(const BV& b, const CV& c, stream_t stream) {
    if (c.size() != kept_count_ || b.size() > 0x80000000u) return false;
    changed_.fill(0u, stream);
    launch(Device{}, c.size(), detail::ComparePairs<BV, CV>{b, c, kept_a_.data(), kept_b_.data(), changed_.data()},
           stream);
    return detail::read_back<Device>(changed_.data(), 0, stream) == 0;
  }
  template <class BV, class CV>
  void keep_pairs(const BV& b, const CV& c, stream_t stream) {
    if (b.size() > 0x80000000u) return;
    gpusolve::detail::ensure_size(kept_a_, c.size());
    gpusolve::detail::ensure_size(kept_b_, c.size());
    if (changed_.size_x() == 0) changed_.resize(1);
    launch(Device{}, c.size(), detail::KeepPairs<BV, CV>{b, c, kept_a_.data(), kept_b_.data()}, stream);
    kept_count_ = c.size();
  }

  // Every pair's colour in colour_, in rounds (see the class); returns the colours used.
  template <class BV, class CV>
  std::uint32_t colour(const BV& b, const CV& c, stream_t stream) {
    const std::size_t nc = c.size();
    const Device dev{};
    grouping_.build(b, c, stream);
    gpusolve::detail::ensure_size(colour_, nc);
    gpusolve::detail::ensure_size(best_, b.size());
    if (counters_.size_x() == 0) counters_.resize(1);
    counters_.fill(detail::ColouringCounters{}, stream);
    launch(dev, nc, detail::MarkPairs<CV>{c, colour_.data(), counters_.data()}, stream);  // every colour_ entry
    const auto g = grouping_.view();
    using GV = decltype(g);
    std::uint32_t round = 0, coloured = 0, colours = 0;
    // Rounds in batches between read-backs: every round colours at least the
    // contact of smallest key, and most finish in a few dozen. The first batch
    // runs a quarter more rounds than the last build needed (the contacts
    // change little from step to step), so that most builds read back once;
    // the batches after it start at 4 and double.
    std::uint32_t batch = needed_ != 0 ? needed_ + needed_ / 4 + 2 : 4;
    for (bool first = true; coloured < nc; batch = first ? 4 : 2 * batch, first = false) {
      for (std::uint32_t r = 0; r < batch; ++r, ++round) {
        launch(dev, b.size(), detail::SmallestUncoloured<BV, GV>{b, g, colour_.data(), best_.data()}, stream);
        launch(dev, nc, detail::PickColour<BV, CV, GV>{b, c, g, colour_.data(), best_.data(), round, counters_.data()},
               stream);
      }
      const detail::ColouringCounters counted = detail::read_back<Device>(counters_.data(), 0, stream);
      coloured = counted.coloured, colours = counted.colours, needed_ = counted.rounds;
    }
    rounds_ = round;
    return colours;
  }

  // order_: the contacts by colour (a stable sort of their indices, later
  // points, marked `follows`, last); bounds_ and offsets_: where each colour starts.
  void sort_by_colour(std::size_t nc, std::uint32_t colours, stream_t stream) {
    const Device dev{};
    for (U32* v : {&order_, &sorted_colour_, &sequence_}) gpusolve::detail::ensure_size(*v, nc);
    launch(dev, nc, detail::Sequence{sequence_.data()}, stream);
    algorithms_.stable_sort_pairs(colour_.data(), sorted_colour_.data(), sequence_.data(), order_.data(), nc, 32,
                                  stream);
    gpusolve::detail::ensure_size(bounds_, colours + 1);
    launch(dev, colours + 1, detail::ColourBounds{sorted_colour_.data(), nc, bounds_.data()}, stream);
    offsets_.resize(colours + 1);
    bounds_host_.resize(bounds_.size_x());
    bounds_host_ = bounds_;  // one copy back: the host sizes each colour's phase
    for (std::size_t k = 0; k <= colours; ++k) offsets_[k] = bounds_host_(k);
  }

  ContactGrouping<Device> grouping_;
  detail::DeviceAlgorithms<Device> algorithms_;
  U32 colour_, sorted_colour_, order_, bounds_, sequence_;
  U32 kept_a_, kept_b_, changed_;  // the last build's pairs (KeepPairs), and what compares them
  VectorD1<detail::ColouringCounters, device_is<Device>> counters_;  // one, read back in one copy per batch
  VectorD1<std::uint32_t, device_is<device::cpu>> bounds_host_;
  VectorD1<std::uint64_t, device_is<Device>> best_;
  std::vector<std::size_t> offsets_{0};
  std::size_t rounds_ = 0, kept_count_ = 0;
  std::uint32_t needed_ = 0;
  bool kept_ = false;
};

}  // namespace gpusolve::rbd
