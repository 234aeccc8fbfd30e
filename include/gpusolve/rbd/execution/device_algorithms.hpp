// DeviceAlgorithms: the device-wide scan, reductions and sort of a time step, queued
// on a stream with one temporary buffer kept between calls, so that a warm step
// allocates nothing and never waits for the device. GPU: CUB; host: sequential
// loops with the same results.
#pragma once

#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <type_traits>
#include <vector>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"

#if GPUSOLVE_HAS_NVCC
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#endif

namespace gpusolve::rbd::detail {

// Reduction operators (namespace scope: nvcc needs kernel arguments' types visible).
struct MaxOp {
  template <class T>
  GPUSOLVE_HD T operator()(const T& a, const T& b) const {
    return a < b ? b : a;
  }
};
struct MinOp {
  template <class T>
  GPUSOLVE_HD T operator()(const T& a, const T& b) const {
    return b < a ? b : a;
  }
};
struct PlusOp {
  template <class T>
  GPUSOLVE_HD T operator()(const T& a, const T& b) const {
    return a + b;
  }
};

// values[i] = f(i): the first pass of a GPU reduction.
template <class F, class T>
struct EvaluateInto {
  F f;
  T* values;
  GPUSOLVE_HD void operator()(std::size_t i) const { values[i] = f(i); }
};

template <class Device>
class DeviceAlgorithms {
  static constexpr bool gpu = std::is_same_v<Device, device::gpu>;

 public:
  // out[i] = in[0] + ... + in[i].
  template <class U>
  void inclusive_sum(const U* in, U* out, std::size_t n, stream_t stream) {
    if (n == 0) return;
    if constexpr (gpu) {
#if GPUSOLVE_HAS_NVCC
      run([&](void* temp, std::size_t& bytes) {
        return cub::DeviceScan::InclusiveSum(temp, bytes, in, out, items(n), stream);
      });
#else
      unsupported();
#endif
    } else {
      (void)stream;
      std::inclusive_scan(in, in + n, out);
    }
  }

  // *out = init op f(0) op ... op f(n - 1), left in the backend's memory. On
  // the GPU a kernel one thread per index writes f(i) into a kept buffer and
  // CUB reduces that: fused into CUB's reduction, f ran on a few blocks, many
  // indices per thread, one after another (docs/tuning/execution.md).
  template <class F, class T, class Op>
  void reduce_into(std::size_t n, F f, T init, Op op, T* out, stream_t stream) {
    if constexpr (gpu) {
      evaluate_and_reduce(n, f, init, op, out, stream);
    } else {
      (void)stream;
      T r = init;
      for (std::size_t i = 0; i < n; ++i) r = op(r, f(i));
      *out = r;
    }
  }

  // reduce_into(), with every f(i) evaluated once, in parallel, on both
  // backends, before the values are reduced in index order: f(i) may update
  // index i's own state first.
  template <class F, class T, class Op>
  void evaluate_and_reduce(std::size_t n, F f, T init, Op op, T* out, stream_t stream) {
    T* values = values_for<T>(n);
    launch(Device{}, n, EvaluateInto<F, T>{f, values}, stream);
    reduce_values(values, n, init, op, out, stream);
  }

  // *out = init op values[0] op ... op values[n - 1], for values already in the
  // backend's memory (no evaluation pass), left there.
  template <class T, class Op>
  void reduce_values(const T* values, std::size_t n, T init, Op op, T* out, stream_t stream) {
    if constexpr (gpu) {
#if GPUSOLVE_HAS_NVCC
      run([&](void* temp, std::size_t& bytes) {
        return cub::DeviceReduce::Reduce(temp, bytes, values, out, items(n), op, init, stream);
      });
#else
      unsupported();
#endif
    } else {
      (void)stream;
      T r = init;
      for (std::size_t i = 0; i < n; ++i) r = op(r, values[i]);
      *out = r;
    }
  }

  template <class F, class T>
  void max_into(std::size_t n, F f, T init, T* out, stream_t stream) {
    reduce_into(n, f, init, MaxOp{}, out, stream);
  }

  // keys_out and values_out: the n pairs (keys_in[i], values_in[i]) ordered by
  // key, pairs of equal keys in their order (stable); every key is below
  // 2^key_bits, the bits a GPU radix sort looks at. Unlike thrust's sorts it
  // neither allocates nor waits for the device once the kept buffer is warm.
  template <class K, class V>
  void stable_sort_pairs(const K* keys_in, K* keys_out, const V* values_in, V* values_out, std::size_t n,
                         int key_bits, stream_t stream) {
    if (n == 0) return;
    if constexpr (gpu) {
#if GPUSOLVE_HAS_NVCC
      run([&](void* temp, std::size_t& bytes) {
        return cub::DeviceRadixSort::SortPairs(temp, bytes, keys_in, keys_out, values_in, values_out, items(n), 0,
                                               key_bits, stream);
      });
#else
      unsupported();
#endif
    } else {
      (void)key_bits, (void)stream;
      std::vector<std::size_t> order(n);
      for (std::size_t i = 0; i < n; ++i) order[i] = i;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return keys_in[x] < keys_in[y]; });
      for (std::size_t i = 0; i < n; ++i) keys_out[i] = keys_in[order[i]], values_out[i] = values_in[order[i]];
    }
  }

  // Grows the kept buffer for reduce_into(n, f, init, op, out) now, so that
  // the call itself allocates nothing (it may then be captured into a graph).
  template <class F, class T, class Op>
  void reserve_reduce(std::size_t n, F f, T init, Op op, T* out) {
    if constexpr (gpu) {
#if GPUSOLVE_HAS_NVCC
      (void)f;
      T* values = values_for<T>(n);
      std::size_t bytes = 0;
      GPUSOLVE_CUDA_CHECK(cub::DeviceReduce::Reduce(nullptr, bytes, values, out, items(n), op, init, stream_t{}));
      grow(bytes);
#else
      unsupported();
#endif
    } else {
      (void)n, (void)f, (void)init, (void)op, (void)out;
    }
  }

  // Bytes of temporary storage held (GPU; stays put once warm).
  std::size_t scratch_bytes() const { return temp_.size_x() + values_.size_x(); }

 private:
  static int items(std::size_t n) {
    if (n > std::size_t(INT_MAX)) throw InvalidArgumentError("gpusolve: a device-wide algorithm got more than INT_MAX items");
    return int(n);
  }
  // A CUB call twice: the size query, then the work in the kept buffer (grown when short).
  template <class Call>
  void run(Call&& call) {
    std::size_t bytes = 0;
    GPUSOLVE_CUDA_CHECK(call(nullptr, bytes));
    grow(bytes);
    GPUSOLVE_CUDA_CHECK(call(static_cast<void*>(temp_.data()), bytes));
  }
  void grow(std::size_t bytes) {
    if (temp_.size_x() < bytes) temp_.resize(bytes + bytes / 2);
  }
  // The kept buffer of a reduction's values, n of them (device allocations are aligned for any T).
  template <class T>
  T* values_for(std::size_t n) {
    const std::size_t bytes = (n > 0 ? n : 1) * sizeof(T);
    if (values_.size_x() < bytes) values_.resize(bytes + bytes / 2);
    return reinterpret_cast<T*>(values_.data());
  }
  [[noreturn]] static void unsupported() {
    throw UnsupportedError("gpusolve: device-wide algorithms on device::gpu need this translation unit compiled by nvcc");
  }

  VectorD1<std::uint8_t, device_is<Device>> temp_, values_;  // CUB's temporary storage; a reduction's values
};

}  // namespace gpusolve::rbd::detail
