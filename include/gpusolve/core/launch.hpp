// The launch layer: runs one __host__ __device__ functor over an index range,
// as a CUDA kernel for device::gpu and as a loop for device::cpu.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/device_facts.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve {

// Calls f(i) for every i in [0, n) on the host. Iterations must be independent;
// they run in parallel when the translation unit is built with OpenMP.
template <class F>
void launch(device::cpu, std::size_t n, F f, stream_t = stream_t{}) {
  const auto count = static_cast<std::int64_t>(n);
#if defined(_OPENMP)
#pragma omp parallel for schedule(static)
#endif
  for (std::int64_t i = 0; i < count; ++i) f(static_cast<std::size_t>(i));
}

#if GPUSOLVE_HAS_NVCC
namespace detail {

// Grid-stride loop: one kernel body serves any n with a bounded grid.
template <class F>
__global__ void for_each_index_kernel(std::size_t n, F f) {
  const std::size_t stride = static_cast<std::size_t>(blockDim.x) * gridDim.x;
  for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < n;
       i += stride)
    f(i);
}

}  // namespace detail

inline constexpr unsigned launch_block_size = 256;
// The block size of a launch too small to give every SM a block of
// launch_block_size: a small scene's walks and updates are chains of dependent
// loads, and spread over all SMs they share fewer load units and L1 caches.
inline constexpr unsigned launch_small_block_size = 64;

// Calls f(i) for every i in [0, n) in a CUDA kernel on `stream`; the launch is
// checked, the kernel runs asynchronously.
template <class F>
void launch(device::gpu, std::size_t n, F f, stream_t stream = stream_t{}) {
  if (n == 0) return;
  const std::size_t sms = static_cast<std::size_t>(detail::sm_count());
  const unsigned block = n < sms * launch_block_size ? launch_small_block_size : launch_block_size;
  const std::size_t wanted = (n + block - 1) / block, cap = sms * 32;
  const unsigned blocks = static_cast<unsigned>(wanted < cap ? wanted : cap);
  detail::for_each_index_kernel<<<blocks, block, 0, stream>>>(n, f);
  GPUSOLVE_CUDA_CHECK(cudaGetLastError());
}
#else
// Without nvcc there is no kernel to launch: say so instead of failing to link.
template <class F>
void launch(device::gpu, std::size_t, F, stream_t = stream_t{}) {
  throw UnsupportedError(
      "gpusolve: launch on device::gpu needs this translation unit compiled by nvcc");
}
#endif

}  // namespace gpusolve
