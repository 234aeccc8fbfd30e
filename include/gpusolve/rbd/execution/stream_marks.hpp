// StreamMarks: points marked in a stream's queued work, to learn later, without
// stalling the queue, whether the work before one is done and how long the work
// between two took. CUDA events on the GPU; the host clock on the CPU backend,
// whose work is done by the time it is queued.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd::detail {

template <class Device, std::size_t N>
class StreamMarks {
  static constexpr bool gpu = std::is_same_v<Device, device::gpu>;

 public:
  StreamMarks() = default;
  StreamMarks(const StreamMarks&) = delete;
  StreamMarks& operator=(const StreamMarks&) = delete;
  ~StreamMarks() {
#if GPUSOLVE_HAS_CUDART
    for (cudaEvent_t e : events_)
      if (e) (void)cudaEventDestroy(e);  // no throw from a destructor
#endif
  }

  // Marks point k after the work queued so far on `stream`.
  void mark(std::size_t k, stream_t stream) {
    if constexpr (gpu) {
#if GPUSOLVE_HAS_CUDART
      if (!events_[k]) GPUSOLVE_CUDA_CHECK(cudaEventCreate(&events_[k]));
      GPUSOLVE_CUDA_CHECK(cudaEventRecord(events_[k], stream));
#else
      (void)k, (void)stream;
      throw UnsupportedError("gpusolve: marking a GPU stream needs the CUDA runtime");
#endif
    } else {
      (void)stream;
      host_[k] = std::chrono::steady_clock::now();
    }
  }

  // Waits until the work before point k is done.
  void wait(std::size_t k) {
#if GPUSOLVE_HAS_CUDART
    if constexpr (gpu) GPUSOLVE_CUDA_CHECK(cudaEventSynchronize(events_[k]));
#endif
    (void)k;
  }

  // Seconds between points `from` and `to`, both marked; waits for `to`.
  double seconds(std::size_t from, std::size_t to) {
    if constexpr (gpu) {
#if GPUSOLVE_HAS_CUDART
      wait(to);
      float ms = 0;
      GPUSOLVE_CUDA_CHECK(cudaEventElapsedTime(&ms, events_[from], events_[to]));
      return 1e-3 * double(ms);
#else
      return 0;
#endif
    } else {
      return std::chrono::duration<double>(host_[to] - host_[from]).count();
    }
  }

 private:
#if GPUSOLVE_HAS_CUDART
  std::array<cudaEvent_t, N> events_{};
#else
  std::array<void*, N> events_{};
#endif
  std::array<std::chrono::steady_clock::time_point, N> host_{};
};

}  // namespace gpusolve::rbd::detail
