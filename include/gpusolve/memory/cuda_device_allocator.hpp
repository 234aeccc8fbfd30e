// CUDADeviceAllocator: GPU global memory from cudaMalloc.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"
#include "gpusolve/memory/cuda_allocation.hpp"

#if GPUSOLVE_HAS_CUDART
namespace gpusolve::memory {

// cudaMalloc returns 256-byte aligned pointers, which the row alignment relies on.
struct CUDADeviceAllocator {
  using memory = device;

  static void* allocate(std::size_t bytes) {
    return detail::cuda_allocate("CUDADeviceAllocator (cudaMalloc)", bytes,
                                 [](void** p, std::size_t b) { return cudaMalloc(p, b); });
  }
  static void deallocate(void* p, std::size_t) noexcept {
    if (p) (void)cudaFree(p);
  }
};

}  // namespace gpusolve::memory
#endif
