// Each backend's Thrust execution policy (the contact colouring's sort and
// search) and read_back(), the one way the host reads a value the backend wrote.
#pragma once

// thrust::host algorithms compile with a plain C++ compiler (g++ with the CCCL
// include directory) as they are; only thrust::device / thrust::cuda need nvcc,
// so they are named under GPUSOLVE_HAS_NVCC alone.
#include <thrust/execution_policy.h>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"

#include <algorithm>
#include <cstddef>
#include <type_traits>

#if GPUSOLVE_HAS_NVCC
#include <thrust/system/cuda/execution_policy.h>
#endif

namespace gpusolve::rbd::detail {

inline auto thrust_policy(device::cpu, stream_t) { return thrust::host; }

#if GPUSOLVE_HAS_NVCC
inline auto thrust_policy(device::gpu, stream_t stream) { return thrust::cuda::par.on(stream); }
#else
// Keeps device::gpu code compiling in host translation units; running it needs nvcc.
[[noreturn]] inline decltype(thrust::host) thrust_policy(device::gpu, stream_t) {
  throw UnsupportedError("gpusolve: collision detection on device::gpu needs this translation unit compiled by nvcc");
}
#endif

// Copies `count` elements between memory owned by Device and the host:
// `to_host`, from the backend's src into the host's dst, else the other way;
// after the stream's work, and the host waits for it.
template <class Device, class U>
void copy_with_host(U* dst, const U* src, std::size_t count, bool to_host, stream_t stream) {
  if (count == 0) return;
  if constexpr (std::is_same_v<Device, device::cpu>) {
    (void)to_host, (void)stream;
    std::copy(src, src + count, dst);
  } else {
#if GPUSOLVE_HAS_CUDART
    GPUSOLVE_CUDA_CHECK(cudaMemcpyAsync(dst, src, count * sizeof(U),
                                        to_host ? cudaMemcpyDeviceToHost : cudaMemcpyHostToDevice, stream));
    GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(stream));
#else
    throw UnsupportedError("gpusolve: reading or writing device memory needs the CUDA runtime");
#endif
  }
}

// Reads element `index` of memory owned by Device, after the stream's work.
template <class Device, class U>
U read_back(const U* p, std::size_t index, stream_t stream) {
  U value{};
  copy_with_host<Device>(&value, p + index, 1, true, stream);
  return value;
}

}  // namespace gpusolve::rbd::detail
