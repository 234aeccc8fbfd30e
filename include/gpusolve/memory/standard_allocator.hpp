// StandardAllocator: pageable host memory from aligned operator new.
#pragma once

#include <cstddef>
#include <new>

#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"

namespace gpusolve::memory {

struct StandardAllocator {
  using memory = host;

  // Aligned so that padded rows start on 128-byte boundaries like device rows.
  static void* allocate(std::size_t bytes) {
    if (bytes == 0) return nullptr;
    // The nothrow form reports failure as a null pointer, which every runtime
    // (AddressSanitizer's too) hands back instead of aborting.
    void* p = ::operator new(bytes, std::align_val_t{allocation_alignment}, std::nothrow);
    if (!p) throw OutOfMemoryError(bytes, detail::oom_message("StandardAllocator", bytes, "operator new"));
    return p;
  }
  static void deallocate(void* p, std::size_t) noexcept {
    if (p) ::operator delete(p, std::align_val_t{allocation_alignment});
  }
};

}  // namespace gpusolve::memory
