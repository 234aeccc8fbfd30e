// Stopwatch for the performance policy: CUDA events on a stream, or the host clock.
#pragma once

#include <chrono>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::runtime {

// Started on construction. With `on_stream`, events bracket the work queued on
// `stream` and seconds() waits for it; otherwise it reads the host clock.
class Stopwatch {
 public:
  explicit Stopwatch(bool on_stream, stream_t stream = stream_t{}) : on_stream_(on_stream), stream_(stream) {
    if (on_stream_) {
#if GPUSOLVE_HAS_CUDART
      GPUSOLVE_CUDA_CHECK(cudaEventCreate(&start_));
      GPUSOLVE_CUDA_CHECK(cudaEventCreate(&stop_));
      GPUSOLVE_CUDA_CHECK(cudaEventRecord(start_, stream_));
#else
      throw UnsupportedError("gpusolve: timing on a stream needs the CUDA runtime");
#endif
    }
    host_start_ = std::chrono::steady_clock::now();
  }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;
  ~Stopwatch() {
#if GPUSOLVE_HAS_CUDART
    if (start_) (void)cudaEventDestroy(start_);
    if (stop_) (void)cudaEventDestroy(stop_);
#endif
  }

  // Seconds since construction; waits for the stream's work when timing on one.
  double seconds() {
#if GPUSOLVE_HAS_CUDART
    if (on_stream_) {
      GPUSOLVE_CUDA_CHECK(cudaEventRecord(stop_, stream_));
      GPUSOLVE_CUDA_CHECK(cudaEventSynchronize(stop_));
      float ms = 0;
      GPUSOLVE_CUDA_CHECK(cudaEventElapsedTime(&ms, start_, stop_));
      return ms * 1e-3;
    }
#endif
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - host_start_).count();
  }

 private:
  bool on_stream_;
  stream_t stream_;
#if GPUSOLVE_HAS_CUDART
  cudaEvent_t start_ = nullptr, stop_ = nullptr;
#endif
  std::chrono::steady_clock::time_point host_start_;
};

}  // namespace gpusolve::runtime
