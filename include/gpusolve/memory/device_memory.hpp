// DeviceMemory: a typed block of GPU global memory (CUDADeviceAllocator by default).
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/memory/cuda_device_allocator.hpp"

#if GPUSOLVE_HAS_CUDART
namespace gpusolve::memory {

// No host element access: the host cannot dereference device pointers.
template <class T, class Alloc = CUDADeviceAllocator>
class DeviceMemory : public Buffer<T, Alloc> {
  static_assert(std::is_same_v<typename Alloc::memory, device>,
                "gpusolve: DeviceMemory needs an allocator whose memory is device");

 public:
  using Buffer<T, Alloc>::Buffer;
};

}  // namespace gpusolve::memory
#endif
