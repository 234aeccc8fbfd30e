// ensure_size(): storage that only grows, reused from step to step (scratch of the rbd kernels).
#pragma once

#include <cstddef>
#include <utility>

#include "gpusolve/core/config.hpp"
#include "gpusolve/memory/copy.hpp"

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

// ensure_size() that keeps the contents: a store read again after it grew
// (the warm start's impulses, which a step held and queued again still
// carries) moves its elements into the larger one, in stream order.
template <class V>
bool ensure_size_keeping(V& v, std::size_t n, std::size_t rows, stream_t stream) {
  if (v.size_x() >= n && v.size_y() == rows) return false;
  V grown;
  if constexpr (V::rank == 1)
    grown.resize(grown_size(v.size_x(), n));
  else
    grown.resize(grown_size(v.size_x(), n), rows);
  if (v.size_y() == rows) {
    using E = typename V::value_type;
    using Kind = typename V::memory_kind;
    memory::copy_rows<Kind, Kind>(grown.data(), grown.pitch() * sizeof(E), v.data(), v.pitch() * sizeof(E),
                                  v.size_x() * sizeof(E), rows, true, stream);
  }
  v = std::move(grown);
  return true;
}

}  // namespace gpusolve::detail
