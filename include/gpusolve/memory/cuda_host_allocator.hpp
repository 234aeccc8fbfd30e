// CUDAHostAllocator: page-locked (pinned) host memory from cudaMallocHost.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"
#include "gpusolve/memory/cuda_allocation.hpp"

#if GPUSOLVE_HAS_CUDART
namespace gpusolve::memory {

// Pinned memory lets copies run as DMA without a staging buffer and lets
// asynchronous copies overlap with kernels. It needs a working driver and GPU:
// without one, allocate throws NoDeviceError.
struct CUDAHostAllocator {
  using memory = pinned;

  static void* allocate(std::size_t bytes) {
    return detail::cuda_allocate("CUDAHostAllocator (cudaMallocHost)", bytes,
                                 [](void** p, std::size_t b) { return cudaMallocHost(p, b); });
  }
  static void deallocate(void* p, std::size_t) noexcept {
    if (p) (void)cudaFreeHost(p);  // no throw from destructors; a failure here leaks nothing new
  }
};

}  // namespace gpusolve::memory
#endif
