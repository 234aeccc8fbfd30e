// LaunchExec: runs a solver's iteration program (see persistent_loop.hpp for the
// contract) as one launch per phase on a stream, on either backend.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"

namespace gpusolve::rbd::detail {

// each(n, f): f(i) for i in [0, n) as one kernel (a loop on the host); sync():
// nothing, stream order already separates the launches; reduce(n, f, init, op,
// out), sum(n, f, out) and scan(in, out, n): through the DeviceAlgorithms it
// was given, whose kept buffers a program that is captured into a graph must
// have reserved (reserve_reduce). With an `exchange` (a distributed solve,
// never captured), every reduction is also reduced over the ranks, and
// combine(bodies) sums the bodies' velocity changes in exchange->sums() over them.
template <class Device, class T>
struct LaunchExec {
  stream_t stream;
  DeviceAlgorithms<Device>* algorithms = nullptr;  // only programs that reduce need one
  BodyExchange<T>* exchange = nullptr;             // only a distributed solve has one
  static constexpr bool exchanges = true;          // programs ask for `exchange` (persistent executors have none)

  template <class F>
  void each(std::size_t n, const F& f) const {
    launch(Device{}, n, f, stream);
  }
  void sync() const {}
  template <class F, class Op>
  void reduce(std::size_t n, const F& f, T init, Op op, T* out) const {
    static_assert(std::is_same_v<Op, MaxOp> || std::is_same_v<Op, PlusOp>,
                  "LaunchExec: a program's reduction is a maximum or a sum (BodyExchange reduces those over ranks)");
    algorithms->reduce_into(n, f, init, op, out, stream);
    if (exchange != nullptr)
      exchange->reduce(out, std::is_same_v<Op, MaxOp> ? ExchangeOp::maximum : ExchangeOp::sum, stream);
  }
  template <class F>
  void sum(std::size_t n, const F& f, T* out) const {
    reduce(n, f, T(0), PlusOp{}, out);
  }
  void combine(std::size_t bodies) const { exchange->combine(bodies, stream); }
  void scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) const {
    algorithms->inclusive_sum(in, out, n, stream);
  }
};

// Whether executor E may carry a BodyExchange (LaunchExec; a persistent
// kernel's executor never does).
template <class E, class = void>
struct may_exchange : std::false_type {};
template <class E>
struct may_exchange<E, std::void_t<decltype(E::exchanges)>> : std::bool_constant<E::exchanges> {};

}  // namespace gpusolve::rbd::detail
