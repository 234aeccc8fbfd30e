// Index-space reductions (max, sum) on a backend through Thrust: the same call
// serves device::cpu and device::gpu and returns the value on the host; and
// MaxReducer, the same max-reduction with its scratch kept for repeated calls.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <thrust/functional.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/transform_reduce.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/detail/thrust_backend.hpp"

#if GPUSOLVE_HAS_NVCC
#include <cub/device/device_reduce.cuh>
#endif

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
// on the GPU, CUB's TransformReduce into temporary storage and a result slot
// kept here, so a warm call allocates nothing and costs one kernel and one
// read-back (Thrust allocates and frees its temporary storage on every call).
// On the host, Thrust's sequential loop, which allocates nothing.
template <class Device, class T>
class MaxReducer {
 public:
  template <class F>
  T operator()(std::size_t n, F f, T init, stream_t stream = stream_t{}) {
#if GPUSOLVE_HAS_NVCC
    if constexpr (std::is_same_v<Device, device::gpu>) {
      if (n == 0) return init;
      if (out_.size_x() == 0) out_.resize(1);
      const thrust::counting_iterator<std::size_t> first(0);
      std::size_t bytes = 0;
      GPUSOLVE_CUDA_CHECK(cub::DeviceReduce::TransformReduce(nullptr, bytes, first, out_.data(), n,
                                                             thrust::maximum<T>(), f, init, stream));
      if (temp_.size_x() < bytes) temp_.resize(bytes);
      GPUSOLVE_CUDA_CHECK(cub::DeviceReduce::TransformReduce(temp_.data(), bytes, first, out_.data(), n,
                                                             thrust::maximum<T>(), f, init, stream));
      return detail::read_back<Device>(out_.data(), 0, stream);
    }
#endif
    return max_over(Device{}, n, f, init, stream);
  }

  // Bytes of temporary storage held (GPU only; stays put once warm).
  std::size_t scratch_bytes() const { return temp_.size_x(); }

 private:
  VectorD1<std::uint8_t, device_is<Device>> temp_;
  VectorD1<T, device_is<Device>> out_;
};

// Sums f(0) ... f(n-1) into *out, memory of the backend, in stream order and
// without the host waiting: a solver's scalars can stay on the device. GPU:
// CUB's TransformReduce into temporary storage kept here; host: a loop.
template <class Device, class T>
class SumInto {
 public:
  // Sizes the temporary storage of a sum over n values of f into out, so that
  // the call itself allocates nothing (it may then be captured into a CUDA graph).
  template <class F>
  void reserve(std::size_t n, F f, T* out) {
#if GPUSOLVE_HAS_NVCC
    if constexpr (std::is_same_v<Device, device::gpu>) {
      const thrust::counting_iterator<std::size_t> first(0);
      std::size_t bytes = 0;
      GPUSOLVE_CUDA_CHECK(
          cub::DeviceReduce::TransformReduce(nullptr, bytes, first, out, n, thrust::plus<T>(), f, T(0), stream_t{}));
      if (temp_.size_x() < bytes) temp_.resize(bytes);
    }
#endif
    (void)n, (void)f, (void)out;
  }

  template <class F>
  void operator()(std::size_t n, F f, T* out, stream_t stream = stream_t{}) {
    if constexpr (std::is_same_v<Device, device::cpu>) {
      (void)stream;
      T s = T(0);
      for (std::size_t i = 0; i < n; ++i) s += f(i);
      *out = s;
    } else {
#if GPUSOLVE_HAS_NVCC
      const thrust::counting_iterator<std::size_t> first(0);
      std::size_t bytes = 0;
      GPUSOLVE_CUDA_CHECK(
          cub::DeviceReduce::TransformReduce(nullptr, bytes, first, out, n, thrust::plus<T>(), f, T(0), stream));
      if (temp_.size_x() < bytes) temp_.resize(bytes);
      GPUSOLVE_CUDA_CHECK(
          cub::DeviceReduce::TransformReduce(temp_.data(), bytes, first, out, n, thrust::plus<T>(), f, T(0), stream));
#else
      (void)n, (void)f, (void)out, (void)stream;
      throw UnsupportedError("gpusolve: a reduction on device::gpu needs this translation unit compiled by nvcc");
#endif
    }
  }

 private:
  VectorD1<std::uint8_t, device_is<Device>> temp_;
};

}  // namespace gpusolve::rbd
