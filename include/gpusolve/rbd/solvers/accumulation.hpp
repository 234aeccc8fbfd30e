// Accumulation strategies: how the velocity updates of all contacts reach their
// bodies in one Jacobi iteration (thesis 5.2 and today's alternatives).
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/contacts/contact_grouping.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/rbd/solvers/packed_velocity.hpp"
#include "gpusolve/rbd/execution/persistent_loop.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"

namespace gpusolve::rbd {

// Strategy tags, the World's Accumulation parameter:
//  - UpdateCache: the thesis's update cache, one slot per contact side grouped by
//    body, summed by ceil(log2 c_max) log-step segmented reduction passes (Listing 12).
//  - Atomic: every contact adds into a per-body accumulator with atomics; order
//    of addition, hence the last bits, vary from run to run on the GPU.
//  - Gather: the update cache summed per body over its segment, one thread per
//    body, in a fixed order: deterministic, one pass, no atomics.
struct UpdateCache {};
struct Atomic {};
struct Gather {};

// Accumulator<Strategy, Device, T>: prepare() once per step after the contacts
// are known, sink() for ResolveCollisions (add(entry, body, dv, dw)), apply()
// adds the iteration's sums to the body velocities (UpdateVelocities) and
// leaves the accumulator ready for the next iteration. program(b, it) is apply()
// as phases of an iteration program (execution/persistent_loop.hpp), the sums
// added to the velocities by the iterate `it` (iterate.hpp; by default to the
// velocities as they are): apply() runs it with a launch per phase, a
// persistent kernel runs it between barriers. Its last phase is left open (no
// sync at the end): the caller may add work that does not touch the velocities to it.
// prepare_program(b, c, stream) is prepare() as a start program, for a solver
// that runs it in its own first kernel: Gather's grouping is built there; the
// other strategies prepare at once (UpdateCache's host needs its pass count)
// and return an empty program. Atomic has besides rotation(b): its iterations
// in one phase each, for a solver without momentum (AtomicRotation).
template <class Strategy, class Device, class T>
class Accumulator;

namespace detail {

template <class Device, class T>
using Vec3Store = VectorD2<T, device_is<Device>>;

// Contact i's changes into the update cache, entry 2i for body a and 2i + 1
// for body b; both slots are looked up before the first store.
template <class T>
struct CacheSink {
  VectorD2View<T> dv, dw;
  VectorD1View<std::uint32_t> slot;
  GPUSOLVE_HD void add(std::size_t i, const BodyResponse<T>& d) const {
    const std::uint32_t pa = slot[2 * i], pb = slot[2 * i + 1];
    if (d.move_a)
      for (std::size_t k = 0; k < 3; ++k) dv(pa, k) = d.dva[k], dw(pa, k) = d.dwa[k];
    if (d.move_b)
      for (std::size_t k = 0; k < 3; ++k) dv(pb, k) = d.dvb[k], dw(pb, k) = d.dwb[k];
  }
};

// One pass of Listing 12 at offset o = 2^(s-1): a sorted position whose rank has
// o as its lowest set bit adds itself into position - o. Ranks stay untouched
// (the thesis zeroed them, which forced a reset every iteration).
template <class T>
struct ReduceVelocityUpdates {
  VectorD2View<T> dv, dw;
  VectorD1View<std::uint32_t> rank;
  std::uint32_t o;
  GPUSOLVE_HD void operator()(std::size_t p) const {
    const std::uint32_t r = rank[p];
    if ((r & o) == 0 || (r & (o - 1)) != 0) return;
    for (std::size_t k = 0; k < 3; ++k) dv(p - o, k) += dv(p, k), dw(p - o, k) += dw(p, k);
  }
};

// UpdateVelocities after the cache was reduced (Sum = false: the segment's first
// position holds the total) or summing the segment here (Sum = true: Gather);
// the iterate (iterate.hpp) adds the sums to the velocities.
template <class BV, class T, bool Sum, class Iterate>
struct CacheToBodies {
  BV b;
  VectorD2View<T> dv, dw;
  VectorD1View<std::uint32_t> start;
  Iterate iterate;
  static constexpr std::uint32_t group = 4;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    T sv[3], sw[3];
    sums(k, sv, sw);
    iterate.add(b, k, sv, sw);
  }
  // Body k's sums over its slots.
  GPUSOLVE_HD void sums(std::size_t k, T (&sv)[3], T (&sw)[3]) const {
    const std::uint32_t first = start[k], end = start[k + 1];
    const std::uint32_t last = (Sum || end == first) ? end : first + 1;
    // `group` slots at a time, their values loaded without a branch between
    // them: one memory round trip per group, not per slot and component. Each
    // sum keeps the order of slots.
    for (std::size_t c = 0; c < 3; ++c) sv[c] = T(0), sw[c] = T(0);
    for (std::uint32_t p = first; p < last; p += group) {
      T gv[group][3], gw[group][3];
      GPUSOLVE_UNROLL
      for (std::uint32_t q = 0; q < group; ++q)
        for (std::size_t c = 0; c < 3; ++c)
          gv[q][c] = p + q < last ? dv(p + q, c) : T(0), gw[q][c] = p + q < last ? dw(p + q, c) : T(0);
      GPUSOLVE_UNROLL
      for (std::uint32_t q = 0; q < group; ++q)
        if (p + q < last)
          for (std::size_t c = 0; c < 3; ++c) sv[c] += gv[q][c], sw[c] += gw[q][c];
    }
  }
};

// A distributed solve's halves of CacheToBodies, with the ranks' sums
// combined between them (BodyExchange::combine): body k's sums of this
// rank's contacts into row k of `out` (dv, then dw) ...
template <class ToBodies, class T>
struct StoreBodySums {
  ToBodies to_bodies;
  VectorD2View<T> out;  // bodies x 6
  GPUSOLVE_HD void operator()(std::size_t k) const {
    T sv[3], sw[3];
    to_bodies.sums(k, sv, sw);
    for (std::size_t c = 0; c < 3; ++c) out(k, c) = sv[c], out(k, 3 + c) = sw[c];
  }
};

// ... and the combined sums added by the iterate.
template <class ToBodies, class T>
struct AddBodySums {
  ToBodies to_bodies;
  VectorD2View<T> in;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    const T sv[3] = {in(k, 0), in(k, 1), in(k, 2)}, sw[3] = {in(k, 3), in(k, 4), in(k, 5)};
    to_bodies.iterate.add(to_bodies.b, k, sv, sw);
  }
};

// A distributed solve's apply(): `take(sums)` is the pass that writes this
// rank's sum of each body into the exchange's store `sums`; the sums are
// combined over the ranks that hold each body, then added.
template <class T, class E, class Take, class ToBodies>
void add_combined_sums(const E& e, std::size_t bodies, const Take& take, const ToBodies& to_bodies) {
  const VectorD2View<T> sums = e.exchange->sums(bodies);
  e.each(bodies, take(sums));
  e.sync();
  e.combine(bodies);
  e.each(bodies, AddBodySums<ToBodies, T>{to_bodies, sums});
}

// The apply() programs of the three strategies.
template <class BV, class T, bool Sum, class Iterate>
struct CacheApply {
  using ToBodies = CacheToBodies<BV, T, Sum, Iterate>;
  ReduceVelocityUpdates<T> pass;  // pass.o is set per pass
  std::size_t passes, entries, bodies;
  ToBodies to_bodies;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    for (std::size_t s = 1; s <= passes; ++s) {
      ReduceVelocityUpdates<T> r = pass;
      r.o = std::uint32_t(1) << (s - 1);
      e.each(entries, r);
      e.sync();
    }
    if constexpr (may_exchange<E>::value)
      if (e.exchange != nullptr) {
        const auto store = [this](VectorD2View<T> sums) { return StoreBodySums<ToBodies, T>{to_bodies, sums}; };
        return add_combined_sums<T>(e, bodies, store, to_bodies);
      }
    e.each(bodies, to_bodies);
  }
};

// Atomic's sums are packed (packed_velocity.hpp): a contact side's atomics
// and a body's loads are two vector accesses each.
template <class T>
struct AtomicSink {
  PackedSums<T> sums;
  std::size_t s;  // the sum added into
  GPUSOLVE_HD void add(std::size_t, const BodyResponse<T>& d) const {
    if (d.move_a) sums.at(s, d.ia).atomic_add(d.dva, d.dwa);
    if (d.move_b) sums.at(s, d.ib).atomic_add(d.dvb, d.dwb);
  }
};

template <class BV, class T, class Iterate>
struct AtomicToBodies {
  BV b;
  PackedSums<T> sums;  // sum 0
  Iterate iterate;
  // Zeroes the sum after the velocities' loads and stores: a store before
  // them would hold the loads back (the views might alias).
  GPUSOLVE_HD void operator()(std::size_t k) const {
    T x[6];
    sums.at(0, k).load(x);
    const T sv[3] = {x[0], x[1], x[2]}, sw[3] = {x[3], x[4], x[5]};
    iterate.add(b, k, sv, sw);
    sums.at(0, k).zero();
  }
};

// A distributed solve's first half of AtomicToBodies: body k's sum into row
// k of `out` (dv, then dw) for BodyExchange::combine, the sum zeroed; the
// combined sums are then added by AddBodySums.
template <class T>
struct TakePackedSums {
  PackedSums<T> sums;   // sum 0
  VectorD2View<T> out;  // bodies x 6
  GPUSOLVE_HD void operator()(std::size_t k) const {
    T x[6];
    sums.at(0, k).load(x);
    for (std::size_t c = 0; c < 6; ++c) out(k, c) = x[c];
    sums.at(0, k).zero();
  }
};

template <class BV, class T, class Iterate>
struct AtomicApply {
  using ToBodies = AtomicToBodies<BV, T, Iterate>;
  ToBodies to_bodies;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    if constexpr (may_exchange<E>::value)
      if (e.exchange != nullptr) {
        const auto take = [this](VectorD2View<T> sums) { return TakePackedSums<T>{to_bodies.sums, sums}; };
        return add_combined_sums<T>(e, to_bodies.b.size(), take, to_bodies);
      }
    e.each(to_bodies.b.size(), to_bodies);
  }
};

// Body j's velocities V and sum A of a rotated phase, as twelve values: V's
// six from the velocity views, then A's six from the packed sums; every load
// is issued before the first use.
template <class T>
GPUSOLVE_HD void load_rotated(const VectorD2View<T>& v, const VectorD2View<T>& w, const PackedPair<T>& a,
                              std::size_t j, T (&x)[12]) {
  T s[6];
  for (std::size_t c = 0; c < 3; ++c) x[c] = v(j, c), x[3 + c] = w(j, c);
  a.load(s);
  for (std::size_t c = 0; c < 6; ++c) x[6 + c] = s[c];
}

// Atomic's iterations in one phase each (AtomicRotation): the contacts of
// iteration k see body j's velocities as V_{k-1}(j) + A_{k-1}(j), the last
// velocities stored plus the last iteration's sums, not yet added.
template <class T>
struct RotatedIterate : CurrentIterate<T> {
  VectorD2View<T> v, w;  // V_{k-1}
  PackedSums<T> sums;
  std::size_t q;  // A_{k-1}
  template <class BV>
  GPUSOLVE_HD void velocity(const BV&, std::uint32_t j, math::Vector3<T>& vj, math::Vector3<T>& wj) const {
    T x[12];
    load_rotated(v, w, sums.at(q, j), j, x);
    vj = math::Vector3<T>(x[0] + x[6], x[1] + x[7], x[2] + x[8]);
    wj = math::Vector3<T>(x[3] + x[9], x[4] + x[10], x[5] + x[11]);
  }
};

// Body j's share of a rotated phase: out = V + A (V from v, w; A sum q), then
// sum `zero` set to zero, and with `two` sum `also` too. load() and store()
// split it so that a phase can put other work between them; every load comes
// before the first store.
template <class T>
struct RotateBody {
  VectorD2View<T> v, w;  // read
  PackedSums<T> sums;
  std::size_t q;
  VectorD2View<T> v_out, w_out;  // written
  std::size_t zero, also;
  bool two;
  GPUSOLVE_HD void load(std::size_t j, T (&x)[12]) const { load_rotated(v, w, sums.at(q, j), j, x); }
  GPUSOLVE_HD void store(std::size_t j, const T (&x)[12]) const {
    for (std::size_t c = 0; c < 3; ++c) v_out(j, c) = x[c] + x[6 + c], w_out(j, c) = x[3 + c] + x[9 + c];
    sums.at(zero, j).zero();
    if (two) sums.at(also, j).zero();
  }
  GPUSOLVE_HD void operator()(std::size_t j) const {
    T x[12];
    load(j, x);
    store(j, x);
  }
};

// Atomic's iterations in one phase and one barrier each, for a solver without
// momentum. Velocities rotate through two buffers (V_0: the bodies' own, V_1:
// a copy), the contacts' sums through three (A_0 is the accumulator's sink).
// In the phase of iteration k (1, 2, ... within a run), contacts read V_{k-1} +
// A_{k-1} (iterate(k)) and add their changes into A_k (sink(k)), and body j
// writes V_k = V_{k-1} + A_{k-1} and zeroes A_{k+1} (body(k)): no phase reads
// what it writes. A run starts with A_0 = A_1 = 0 and V_0 the velocities and
// ends, after its last iteration K and a barrier, with fold(K): the bodies'
// velocities V_K + A_K, and A_K and A_{K-1} zeroed, so every sum is zero again.
template <class T>
struct AtomicRotation {
  VectorD2View<T> v0, w0, v1, w1;
  PackedSums<T> sums;
  GPUSOLVE_HD RotatedIterate<T> iterate(std::size_t k) const {
    const bool p = k % 2 == 0;  // V_{k-1} is V_1
    return {{}, p ? v1 : v0, p ? w1 : w0, sums, (k + 2) % 3};
  }
  GPUSOLVE_HD AtomicSink<T> sink(std::size_t k) const { return {sums, k % 3}; }
  GPUSOLVE_HD RotateBody<T> body(std::size_t k) const {
    const bool p = k % 2 == 0;
    const std::size_t z = (k + 1) % 3;
    return {p ? v1 : v0, p ? w1 : w0, sums, (k + 2) % 3, p ? v0 : v1, p ? w0 : w1, z, z, false};
  }
  GPUSOLVE_HD RotateBody<T> fold(std::size_t k) const {
    const bool p = k % 2 == 1;  // V_k is V_1
    return {p ? v1 : v0, p ? w1 : w0, sums, k % 3, v0, w0, k % 3, (k + 2) % 3, true};
  }
};

// The update cache shared by UpdateCache and Gather: one slot per contact side.
template <class Device, class T>
class CacheStore {
 public:
  template <class BV, class CV>
  void prepare(const BV& b, const CV& c, stream_t stream) {
    size_for(c);
    grouping_.build(b, c, stream);
  }
  template <class BV, class CV>
  auto prepare_program(const BV& b, const CV& c, stream_t stream) {
    size_for(c);
    return grouping_.program(b, c, stream);
  }
  CacheSink<T> sink() { return CacheSink<T>{dv_.view(), dw_.view(), grouping_.view().slot}; }
 protected:
  template <bool Sum, class BV, class Iterate>
  CacheApply<BV, T, Sum, Iterate> cache_program(const BV& b, std::size_t passes, const Iterate& it) {
    const auto g = grouping_.view();
    return {{dv_.view(), dw_.view(), g.rank, 0}, passes, entries_, b.size(),
            {b, dv_.view(), dw_.view(), g.start, it}};
  }
  ContactGrouping<Device> grouping_;
  Vec3Store<Device, T> dv_, dw_;
  std::size_t entries_ = 0;

 private:
  template <class CV>
  void size_for(const CV& c) {
    gpusolve::detail::ensure_size(dv_, 2 * c.bound(), 3);
    gpusolve::detail::ensure_size(dw_, 2 * c.bound(), 3);
    entries_ = 2 * c.bound();
  }
};

}  // namespace detail

template <class Device, class T>
class Accumulator<UpdateCache, Device, T> : public detail::CacheStore<Device, T> {
 public:
  std::size_t passes() { return this->grouping_.passes(); }  // waits for the grouping once per step
  template <class BV, class CV>
  detail::NoStart prepare_program(const BV& b, const CV& c, stream_t stream) {
    this->prepare(b, c, stream);
    return {};
  }
  template <class BV, class Iterate = detail::CurrentIterate<T>>
  detail::CacheApply<BV, T, false, Iterate> program(const BV& b, const Iterate& it = Iterate{}) {
    return this->template cache_program<false>(b, passes(), it);
  }
  template <class BV>
  void apply(const BV& b, stream_t stream = stream_t{}) {
    program(b)(detail::LaunchExec<Device, T>{stream});
  }
};

template <class Device, class T>
class Accumulator<Gather, Device, T> : public detail::CacheStore<Device, T> {
 public:
  std::size_t passes() const { return 0; }
  template <class BV, class Iterate = detail::CurrentIterate<T>>
  detail::CacheApply<BV, T, true, Iterate> program(const BV& b, const Iterate& it = Iterate{}) {
    return this->template cache_program<true>(b, 0, it);
  }
  template <class BV>
  void apply(const BV& b, stream_t stream = stream_t{}) {
    program(b)(detail::LaunchExec<Device, T>{stream});
  }
};

template <class Device, class T>
class Accumulator<Atomic, Device, T> {
 public:
  template <class BV, class CV>
  void prepare(const BV& b, const CV&, stream_t stream = stream_t{}) {
    bodies_ = b.size();
    if (!gpusolve::detail::ensure_size(sums_, 3 * detail::packed_width * bodies_)) sums_.fill(T(0), stream);  // a new store is zero
  }
  template <class BV, class CV>
  detail::NoStart prepare_program(const BV& b, const CV& c, stream_t stream) {
    prepare(b, c, stream);
    return {};
  }
  detail::AtomicSink<T> sink() { return {sums(), 0}; }
  template <class BV, class Iterate = detail::CurrentIterate<T>>
  detail::AtomicApply<BV, T, Iterate> program(const BV& b, const Iterate& it = Iterate{}) {
    return {{b, sums(), it}};
  }
  template <class BV>
  void apply(const BV& b, stream_t stream = stream_t{}) {
    program(b)(detail::LaunchExec<Device, T>{stream});
  }
  // After prepare(): the rotation over b's velocities.
  template <class BV>
  detail::AtomicRotation<T> rotation(const BV& b) {
    gpusolve::detail::ensure_size(copy_, b.size(), 6);
    const auto c = copy_.view();
    return {b.v, b.w, {c.ptr, b.size(), 3, c.pitch}, {c.ptr + 3 * c.pitch, b.size(), 3, c.pitch}, sums()};
  }
  std::size_t passes() const { return 0; }

 private:
  detail::PackedSums<T> sums() { return {sums_.data(), bodies_}; }
  VectorD1<T, device_is<Device>> sums_;  // A_0 (the sink), A_1, A_2, packed
  VectorD2<T, device_is<Device>> copy_;  // V_1 of the rotation: v then w
  std::size_t bodies_ = 0;
};

}  // namespace gpusolve::rbd
