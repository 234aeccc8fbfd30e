// LaunchExec: runs a solver's iteration program (see persistent_loop.hpp for the
// contract) as one launch per phase on a stream, on either backend.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"

namespace gpusolve::rbd::detail {

// each(n, f): f(i) for i in [0, n) as one kernel (a loop on the host); sync():
// nothing, stream order already separates the launches; reduce(n, f, init, op,
// out), sum(n, f, out) and scan(in, out, n): through the DeviceAlgorithms it
// was given, whose kept buffers a program that is captured into a graph must
// have reserved (reserve_reduce).
template <class Device, class T>
struct LaunchExec {
  stream_t stream;
  DeviceAlgorithms<Device>* algorithms = nullptr;  // only programs that reduce need one

  template <class F>
  void each(std::size_t n, const F& f) const {
    launch(Device{}, n, f, stream);
  }
  void sync() const {}
  template <class F, class Op>
  void reduce(std::size_t n, const F& f, T init, Op op, T* out) const {
    algorithms->reduce_into(n, f, init, op, out, stream);
  }
  template <class F>
  void sum(std::size_t n, const F& f, T* out) const {
    reduce(n, f, T(0), PlusOp{}, out);
  }
  void scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) const {
    algorithms->inclusive_sum(in, out, n, stream);
  }
};

}  // namespace gpusolve::rbd::detail
