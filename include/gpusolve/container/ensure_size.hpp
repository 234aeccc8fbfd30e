// ensure_size(): storage that only grows, reused from step to step (scratch of the rbd kernels).
#pragma once

#include <cstddef>

namespace gpusolve::detail {

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

}  // namespace gpusolve::detail
