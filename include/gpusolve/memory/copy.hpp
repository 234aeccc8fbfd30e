// Pitched copies between any two memory kinds (host, pinned, device), synchronous or on a stream.
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"

namespace gpusolve::memory {

#if GPUSOLVE_HAS_CUDART
template <class To, class From>
constexpr cudaMemcpyKind copy_kind() {
  constexpr bool to_host = is_host_accessible_v<To>, from_host = is_host_accessible_v<From>;
  if constexpr (to_host && from_host) return cudaMemcpyHostToHost;
  else if constexpr (to_host) return cudaMemcpyDeviceToHost;
  else if constexpr (from_host) return cudaMemcpyHostToDevice;
  else return cudaMemcpyDeviceToDevice;
}
#endif

// Copies `height` rows of `width` bytes; row r starts at dst + r*dpitch and
// src + r*spitch. Host-to-host copies run on the CPU (no driver needed); any
// copy touching device memory is a cudaMemcpy2D, or cudaMemcpy2DAsync on
// `stream` when `async` (truly asynchronous only from or to pinned memory).
template <class To, class From>
void copy_rows(void* dst, std::size_t dpitch, const void* src, std::size_t spitch,
               std::size_t width, std::size_t height, bool async, stream_t stream) {
  if (width == 0 || height == 0) return;
  if constexpr (is_host_accessible_v<To> && is_host_accessible_v<From>) {
    (void)async;
    (void)stream;
    if (dpitch == width && spitch == width) {
      std::memcpy(dst, src, width * height);
      return;
    }
    for (std::size_t r = 0; r < height; ++r)
      std::memcpy(static_cast<char*>(dst) + r * dpitch, static_cast<const char*>(src) + r * spitch,
                  width);
  } else {
#if GPUSOLVE_HAS_CUDART
    constexpr cudaMemcpyKind kind = copy_kind<To, From>();
    if (async)
      GPUSOLVE_CUDA_CHECK(cudaMemcpy2DAsync(dst, dpitch, src, spitch, width, height, kind, stream));
    else
      GPUSOLVE_CUDA_CHECK(cudaMemcpy2D(dst, dpitch, src, spitch, width, height, kind));
#else
    static_assert(sizeof(To) == 0, "gpusolve: copies to or from device memory need the CUDA runtime");
#endif
  }
}

}  // namespace gpusolve::memory
