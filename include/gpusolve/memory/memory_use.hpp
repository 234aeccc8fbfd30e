// MemoryUse: the bytes gpusolve's buffers hold in each memory kind (host,
// pinned, device), now and at most since the last reset: what a scene costs
// on the GPU, counted where every container allocates (Buffer).
#pragma once

#include <atomic>
#include <cstddef>

#include "gpusolve/memory/allocator.hpp"

namespace gpusolve::memory {

struct MemoryUse {
  std::size_t now = 0;   // bytes held
  std::size_t peak = 0;  // the most held at once since reset_peak<Kind>()
};

namespace detail {
template <class Kind>
struct UseCounter {
  static inline std::atomic<std::size_t> now{0};
  static inline std::atomic<std::size_t> peak{0};
};
}  // namespace detail

template <class Kind>
MemoryUse memory_use() {
  return {detail::UseCounter<Kind>::now.load(), detail::UseCounter<Kind>::peak.load()};
}

// Starts the peak over from what is held now.
template <class Kind>
void reset_peak() {
  detail::UseCounter<Kind>::peak.store(detail::UseCounter<Kind>::now.load());
}

namespace detail {
template <class Kind>
void count_allocation(std::size_t bytes) {
  const std::size_t now = UseCounter<Kind>::now.fetch_add(bytes) + bytes;
  std::size_t peak = UseCounter<Kind>::peak.load();
  while (now > peak && !UseCounter<Kind>::peak.compare_exchange_weak(peak, now)) {
  }
}
template <class Kind>
void count_release(std::size_t bytes) {
  UseCounter<Kind>::now.fetch_sub(bytes);
}
}  // namespace detail

}  // namespace gpusolve::memory
