// Index-space reductions (max, sum) on a backend through Thrust: the same call
// serves device::cpu and device::gpu and returns the value on the host; and
// MaxReducer, the repeated reduction of a solver's residual, with scratch kept.
#pragma once

#include <cstddef>

#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/transform_reduce.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/detail/device_algorithms.hpp"
#include "gpusolve/rbd/detail/thrust_backend.hpp"

namespace gpusolve::rbd {

// Reduces f(0) ... f(n-1) with op from init; for the GPU this waits for the stream.
template <class Device, class F, class T, class Op>
T reduce_indices(Device dev, std::size_t n, F f, T init, Op op, stream_t stream = stream_t{}) {
  if (n == 0) return init;
  const thrust::counting_iterator<std::size_t> first(0);
  return thrust::transform_reduce(detail::thrust_policy(dev, stream), first, first + n, f, init, op);
}

template <class Device, class F, class T>
T max_over(Device dev, std::size_t n, F f, T init, stream_t stream = stream_t{}) {
  return reduce_indices(dev, n, f, init, thrust::maximum<T>(), stream);
}

template <class Device, class F, class T>
T sum_over(Device dev, std::size_t n, F f, T init, stream_t stream = stream_t{}) {
  return reduce_indices(dev, n, f, init, thrust::plus<T>(), stream);
}

// max_over for a reduction repeated many times (the solver's residual check):
// DeviceAlgorithms' reduction into a result slot kept here, read back at once,
// so a warm call allocates nothing and costs one reduction and one read-back
// (Thrust allocates and frees its temporary storage on every call).
template <class Device, class T>
class MaxReducer {
 public:
  template <class F>
  T operator()(std::size_t n, F f, T init, stream_t stream = stream_t{}) {
    if (n == 0) return init;
    if (out_.size_x() == 0) out_.resize(1);
    algorithms_.max_into(n, f, init, out_.data(), stream);
    return detail::read_back<Device>(out_.data(), 0, stream);
  }

  // Bytes of temporary storage held (GPU only; stays put once warm).
  std::size_t scratch_bytes() const { return algorithms_.scratch_bytes(); }

 private:
  detail::DeviceAlgorithms<Device> algorithms_;
  VectorD1<T, device_is<Device>> out_;
};

}  // namespace gpusolve::rbd
