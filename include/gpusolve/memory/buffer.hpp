// Buffer: an owning, move-only block of elements obtained from one allocator.
#pragma once

#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"
#include "gpusolve/memory/memory_use.hpp"

namespace gpusolve::memory {

// Elements are never constructed one by one: T must be trivially copyable
// because its bytes travel between host and device with memcpy/cudaMemcpy.
// A new buffer is zero-filled (all bytes 0), so no element is ever indeterminate.
// Its bytes count in memory_use<memory_kind>() while it holds them.
template <class T, class Alloc>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>,
                "gpusolve: container elements must be trivially copyable (they are copied as bytes)");
  static_assert(is_allocator_v<Alloc>,
                "gpusolve: the allocator must provide `using memory = host|pinned|device`, "
                "static allocate(bytes) and static deallocate(p, bytes)");

 public:
  using value_type = T;
  using allocator_type = Alloc;
  using memory_kind = typename Alloc::memory;

  Buffer() = default;
  explicit Buffer(std::size_t count) : ptr_(allocate(count)), count_(count) { zero(); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& o) noexcept : ptr_(std::exchange(o.ptr_, nullptr)), count_(std::exchange(o.count_, 0)) {}
  Buffer& operator=(Buffer&& o) noexcept {
    if (this != &o) {
      release();
      ptr_ = std::exchange(o.ptr_, nullptr);
      count_ = std::exchange(o.count_, 0);
    }
    return *this;
  }
  ~Buffer() { release(); }

  T* data() noexcept { return ptr_; }
  const T* data() const noexcept { return ptr_; }
  std::size_t size() const noexcept { return count_; }
  std::size_t bytes() const noexcept { return count_ * sizeof(T); }

  // Sets every byte to zero (padding included); on the device asynchronously on `stream`.
  void zero(stream_t stream = stream_t{}) {
    if (bytes() == 0) return;
    if constexpr (is_host_accessible_v<memory_kind>) {
      (void)stream;
      std::memset(static_cast<void*>(ptr_), 0, bytes());
    } else {
#if GPUSOLVE_HAS_CUDART
      GPUSOLVE_CUDA_CHECK(cudaMemsetAsync(ptr_, 0, bytes(), stream));
#else
      static_assert(sizeof(T) == 0, "gpusolve: device memory needs the CUDA runtime");
#endif
    }
  }

 private:
  static T* allocate(std::size_t count) {
    if (count > std::numeric_limits<std::size_t>::max() / sizeof(T))
      throw OutOfMemoryError(std::numeric_limits<std::size_t>::max(),
                             detail::oom_message("Buffer", std::numeric_limits<std::size_t>::max(),
                                                 "the element count overflows the size of an allocation"));
    T* p = static_cast<T*>(Alloc::allocate(count * sizeof(T)));
    detail::count_allocation<memory_kind>(count * sizeof(T));
    return p;
  }
  void release() noexcept {
    detail::count_release<memory_kind>(bytes());
    Alloc::deallocate(ptr_, bytes());
    ptr_ = nullptr;
    count_ = 0;
  }

  T* ptr_ = nullptr;
  std::size_t count_ = 0;
};

}  // namespace gpusolve::memory
