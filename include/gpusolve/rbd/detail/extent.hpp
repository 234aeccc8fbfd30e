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
// live is set: the host would read device memory. No kernel that reads the
// count writes it, so a kernel reads it through the read-only path: a
// persistent kernel's barriers (acquire at the GPU's scope) would send every
// plain load of it back to L2.
struct Extent {
  std::size_t bound = 0;
  const std::uint32_t* live = nullptr;
  GPUSOLVE_HD std::size_t size() const {
    if (live == nullptr) return bound;
#if GPUSOLVE_DEVICE_CODE
    const std::size_t n = __ldg(live);
#else
    const std::size_t n = *live;
#endif
    return n < bound ? n : bound;
  }
};

}  // namespace gpusolve::rbd::detail
