// logical(): a view of a store's capacity-sized field trimmed to its logical size.
#pragma once

#include <cstddef>

#include "gpusolve/container/vector_view.hpp"

namespace gpusolve::detail {

// Bodies and Contacts keep storage beyond their size; kernels see `n` entries.
// A field that was never allocated (a model without it) stays empty.
template <class T, class Check>
VectorD1View<T, Check> logical(VectorD1View<T, Check> v, std::size_t n) {
  if (v.n != 0) v.n = n;
  return v;
}
template <class T, class Check>
VectorD2View<T, Check> logical(VectorD2View<T, Check> v, std::size_t n) {
  if (v.nx != 0) v.nx = n;
  return v;
}

}  // namespace gpusolve::detail
