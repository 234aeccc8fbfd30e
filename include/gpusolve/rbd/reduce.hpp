// Index-space reductions (max, sum) on a backend through Thrust: the same call
// serves device::cpu and device::gpu and returns the value on the host.
#pragma once

#include <cstddef>

#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/transform_reduce.h>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/thrust_backend.hpp"

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

}  // namespace gpusolve::rbd
