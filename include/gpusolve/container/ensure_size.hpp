// ensure_size(): storage that only grows, reused from step to step (scratch of the rbd kernels).
#pragma once

#include <cstddef>

namespace gpusolve::detail {

// The size a store of `had` elements grows to for n: n itself the first time
// (a size set once, as the bodies' count, needs no slack), then by half again,
// so that slowly growing sizes (the contacts of a settling pile) do not
// reallocate every step.
inline std::size_t grown_size(std::size_t had, std::size_t n) { return had == 0 ? n : n + n / 2; }

// Grows a VectorD1 to at least n elements (grown_size). Returns whether it
// reallocated (contents are then lost and zero).
template <class V>
bool ensure_size(V& v, std::size_t n) {
  if (v.size_x() >= n) return false;
  v.resize(grown_size(v.size_x(), n));
  return true;
}

// The same for a VectorD2 of n x rows.
template <class V>
bool ensure_size(V& v, std::size_t n, std::size_t rows) {
  if (v.size_x() >= n && v.size_y() == rows) return false;
  v.resize(grown_size(v.size_x(), n), rows);
  return true;
}

}  // namespace gpusolve::detail
