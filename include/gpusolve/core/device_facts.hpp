// per_device(): a fact about the current CUDA device (an attribute, a kernel's
// occupancy) read once per device and process, so that a program that moves
// between devices never uses another device's figure.
#pragma once

#include <atomic>
#include <cstring>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

#if GPUSOLVE_HAS_CUDART
namespace gpusolve::detail {

// Devices whose facts are kept; a device past them is asked every time.
inline constexpr int cached_devices = 64;

inline int current_device() {
  int dev = 0;
  GPUSOLVE_CUDA_CHECK(cudaGetDevice(&dev));
  return dev;
}

// Whether every visible device is the same model (name, compute capability,
// multiprocessors): then a fact read on one holds on all, and asking which
// device is current (a runtime call per launch) can be skipped.
inline bool devices_alike() {
  static const bool alike = [] {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess || count <= 1) return true;
    cudaDeviceProp first{};
    GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&first, 0));
    for (int d = 1; d < count; ++d) {
      cudaDeviceProp p{};
      GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&p, d));
      if (std::strcmp(p.name, first.name) != 0 || p.major != first.major || p.minor != first.minor ||
          p.multiProcessorCount != first.multiProcessorCount)
        return false;
    }
    return true;
  }();
  return alike;
}

// read(dev) for the current device, a non-negative int, computed on the first
// call for that device (for every device at once where they are alike). Each
// Read type (a lambda at its one call site) keeps its own table; two threads
// may both read a fact the first time, with one result.
template <class Read>
int per_device(Read read) {
  if (devices_alike()) {
    static const int everywhere = read(current_device());
    return everywhere;
  }
  static std::atomic<int> known[cached_devices];  // value + 1; 0: not read yet
  const int dev = current_device();
  if (dev >= cached_devices) return read(dev);
  int v = known[dev].load(std::memory_order_relaxed);
  if (v == 0) {
    v = read(dev) + 1;
    known[dev].store(v, std::memory_order_relaxed);
  }
  return v - 1;
}

// The current device's number of multiprocessors.
inline int sm_count() {
  return per_device([](int dev) {
    int sms = 0;
    GPUSOLVE_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev));
    return sms;
  });
}

}  // namespace gpusolve::detail
#endif
