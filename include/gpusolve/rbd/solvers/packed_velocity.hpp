// A body's velocity pair (v, w) packed into eight values: v in [0, 3), w in
// [4, 7), the other two zero. In float that is 32 bytes, one memory sector, so
// a gather of it or an atomic sum into it costs two 16-byte vector accesses on
// the GPU instead of six scalar ones into six arrays (Atomic's sums,
// accumulation.hpp). The update cache keeps its six arrays: a body's segment
// of slots is contiguous, so its scalar loads coalesce, and packed slots
// measured slower at small sizes.
#pragma once

#include <cstddef>
#include <type_traits>

#include <cuda/atomic>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd::detail {

inline constexpr std::size_t packed_width = 8;

template <class T>
struct PackedPair {
  T* p;  // aligned to 4 values

  GPUSOLVE_HD void load(T (&x)[6]) const {
#if GPUSOLVE_DEVICE_CODE
    if constexpr (std::is_same_v<T, float>) {
      const float4 a = reinterpret_cast<const float4*>(p)[0], b = reinterpret_cast<const float4*>(p)[1];
      x[0] = a.x, x[1] = a.y, x[2] = a.z, x[3] = b.x, x[4] = b.y, x[5] = b.z;
    } else
#endif
    {
      for (std::size_t c = 0; c < 3; ++c) x[c] = p[c], x[3 + c] = p[4 + c];
    }
  }
  GPUSOLVE_HD void store(const T (&x)[6]) const {
#if GPUSOLVE_DEVICE_CODE
    if constexpr (std::is_same_v<T, float>) {
      reinterpret_cast<float4*>(p)[0] = make_float4(x[0], x[1], x[2], 0.f);
      reinterpret_cast<float4*>(p)[1] = make_float4(x[3], x[4], x[5], 0.f);
    } else
#endif
    {
      for (std::size_t c = 0; c < 3; ++c) p[c] = x[c], p[4 + c] = x[3 + c];
      p[3] = p[7] = T(0);
    }
  }
  GPUSOLVE_HD void zero() const {
    const T z[6] = {};
    store(z);
  }
  // Adds (v, w) with relaxed atomics: on sm_90 and later two vector atomics.
  GPUSOLVE_HD void atomic_add(const math::Vector3<T>& v, const math::Vector3<T>& w) const {
#if GPUSOLVE_DEVICE_CODE && __CUDA_ARCH__ >= 900
    if constexpr (std::is_same_v<T, float>) {
      atomicAdd(reinterpret_cast<float4*>(p), make_float4(v[0], v[1], v[2], 0.f));
      atomicAdd(reinterpret_cast<float4*>(p) + 1, make_float4(w[0], w[1], w[2], 0.f));
    } else
#endif
    {
      for (std::size_t c = 0; c < 3; ++c) {
        cuda::atomic_ref<T, cuda::thread_scope_device>(p[c]).fetch_add(v[c], cuda::std::memory_order_relaxed);
        cuda::atomic_ref<T, cuda::thread_scope_device>(p[4 + c]).fetch_add(w[c], cuda::std::memory_order_relaxed);
      }
    }
  }
};

// `count` packed pairs per sum, sums one after another: pair j of sum s.
template <class T>
struct PackedSums {
  T* base;
  std::size_t count;
  GPUSOLVE_HD PackedPair<T> at(std::size_t s, std::size_t j) const {
    return {base + packed_width * (s * count + j)};
  }
};

}  // namespace gpusolve::rbd::detail
