// per_device(): a fact about the current CUDA device (an attribute, a kernel's
// occupancy) read once per device and process, so that a program that moves
// between devices never uses another device's figure.
#pragma once

#include <atomic>

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

// read(dev) for the current device, a non-negative int, computed on the first
// call for that device. Each Read type (a lambda at its one call site) keeps its
// own table; two threads may both read a fact the first time, with one result.
template <class Read>
int per_device(Read read) {
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
