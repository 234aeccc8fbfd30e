// Extent: a count whose bound the host knows and whose value may live only in
// the backend's memory (a step queued without a host wait).
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd::detail {

// The host sizes storage and launches by `bound`; kernels read size(): the
// count a kernel earlier in the stream wrote to *live (World::advance_unattended:
// the contact count of the step's detection), at most the bound, or the bound
// itself where live is null. On the GPU only kernels may call size() while
// live is set: the host would read device memory.
struct Extent {
  std::size_t bound = 0;
  const std::uint32_t* live = nullptr;
  GPUSOLVE_HD std::size_t size() const {
    if (live == nullptr) return bound;
    const std::size_t n = *live;
    return n < bound ? n : bound;
  }
};

}  // namespace gpusolve::rbd::detail
