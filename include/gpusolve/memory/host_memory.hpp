// HostMemory: a typed block of host memory, pageable (StandardAllocator) or pinned (CUDAHostAllocator).
#pragma once

#include <cstddef>

#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/memory/standard_allocator.hpp"

namespace gpusolve::memory {

template <class T, class Alloc = StandardAllocator>
class HostMemory : public Buffer<T, Alloc> {
  static_assert(is_host_accessible_v<typename Alloc::memory>,
                "gpusolve: HostMemory needs an allocator whose memory is host or pinned");

 public:
  using Buffer<T, Alloc>::Buffer;
  T& operator()(std::size_t i) { return this->data()[i]; }
  const T& operator()(std::size_t i) const { return this->data()[i]; }
};

}  // namespace gpusolve::memory
