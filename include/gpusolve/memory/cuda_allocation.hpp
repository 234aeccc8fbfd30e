// Shared error handling of the CUDA allocators: out of memory vs. no device vs. other failures.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"

#if GPUSOLVE_HAS_CUDART
namespace gpusolve::memory::detail {

// Calls alloc(&p, bytes) and turns its status into the library's typed errors.
template <class Alloc>
void* cuda_allocate(const char* who, std::size_t bytes, Alloc alloc) {
  if (bytes == 0) return nullptr;
  void* p = nullptr;
  const cudaError_t e = alloc(&p, bytes);
  if (e == cudaErrorMemoryAllocation) {
    (void)cudaGetLastError();
    throw OutOfMemoryError(bytes, oom_message(who, bytes, cudaGetErrorString(e)));
  }
  // Everything else (no device, no driver) gets the common typed errors.
  ::gpusolve::detail::check_cuda(e, who, __FILE__, __LINE__);
  return p;
}

}  // namespace gpusolve::memory::detail
#endif
