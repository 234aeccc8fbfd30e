// Scratch storage of the rbd kernels: vectors that only grow, reused step to step.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd::detail {

// Grows a VectorD1 to at least n elements, by half again so that slowly growing
// sizes do not reallocate every step. Returns whether it reallocated (contents
// are then lost and zero).
template <class V>
bool ensure_size(V& v, std::size_t n) {
  if (v.size_x() >= n) return false;
  v.resize(n + n / 2);
  return true;
}

// The same for a VectorD2 of n x rows.
template <class V>
bool ensure_size(V& v, std::size_t n, std::size_t rows) {
  if (v.size_x() >= n && v.size_y() == rows) return false;
  v.resize(n + n / 2, rows);
  return true;
}

// A phase that zeroes a scratch vector of counts (a view of std::uint32_t),
// for programs that clear their counters between barriers.
template <class U32View>
struct ZeroU32 {
  U32View v;
  GPUSOLVE_HD void operator()(std::size_t i) const { v[i] = 0u; }
};

}  // namespace gpusolve::rbd::detail
