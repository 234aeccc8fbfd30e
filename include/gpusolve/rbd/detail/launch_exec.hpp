// LaunchExec: runs a solver's iteration program (see persistent_loop.hpp for the
// contract) as one launch per phase on a stream, on either backend.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"

namespace gpusolve::rbd::detail {

// each(n, f): f(i) for i in [0, n) as one kernel (a loop on the host); sync():
// nothing, stream order already separates the launches; sum(n, f, out): the
// sum of f(i) into *out (backend memory) through the SumInto it was given.
template <class Device, class T>
struct LaunchExec {
  stream_t stream;
  SumInto<Device, T>* summer = nullptr;  // only programs that call sum() need one

  template <class F>
  void each(std::size_t n, const F& f) const {
    launch(Device{}, n, f, stream);
  }
  void sync() const {}
  template <class F>
  void sum(std::size_t n, const F& f, T* out) const {
    (*summer)(n, f, out, stream);
  }
};

}  // namespace gpusolve::rbd::detail
