// Non-owning, trivially copyable views of VectorD1/D2/D3 storage: what kernels
// take by value. Layout: x is contiguous, then y, then z (column-major), each
// dimension padded to the container's pitch.
#pragma once

#include <cstddef>
#include <type_traits>

#include "gpusolve/container/bounds.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/policy/compiletime.hpp"

namespace gpusolve {

template <class T, class Check = compiletime::ReleasePolicy>
struct VectorD1View {
  T* ptr = nullptr;
  std::size_t n = 0;

  GPUSOLVE_HD T* data() const { return ptr; }
  GPUSOLVE_HD std::size_t size() const { return n; }
  GPUSOLVE_HD T& operator[](std::size_t i) const {
    if constexpr (Check::bounds_check) {
      if (i >= n) detail::bounds_violation(1, i, 0, 0, n, 0, 0);
    }
    return ptr[i];
  }
  GPUSOLVE_HD T& operator()(std::size_t i) const { return (*this)[i]; }
};

template <class T, class Check = compiletime::ReleasePolicy>
struct VectorD2View {
  T* ptr = nullptr;
  std::size_t nx = 0, ny = 0;
  std::size_t pitch = 0;  // elements between the starts of rows j and j+1 (padded nx)

  GPUSOLVE_HD T* data() const { return ptr; }
  GPUSOLVE_HD std::size_t size_x() const { return nx; }
  GPUSOLVE_HD std::size_t size_y() const { return ny; }
  GPUSOLVE_HD T& operator()(std::size_t i, std::size_t j) const {
    if constexpr (Check::bounds_check) {
      if (i >= nx || j >= ny) detail::bounds_violation(2, i, j, 0, nx, ny, 0);
    }
    return ptr[j * pitch + i];
  }
  // Access by a precomputed linear offset (see VectorD2Offset). Unchecked by
  // design: the offset was built from this view's pitch.
  GPUSOLVE_HD T& operator()(std::size_t linear) const { return ptr[linear]; }
};

template <class T, class Check = compiletime::ReleasePolicy>
struct VectorD3View {
  T* ptr = nullptr;
  std::size_t nx = 0, ny = 0, nz = 0;
  std::size_t pitch_x = 0;  // padded nx
  std::size_t pitch_y = 0;  // padded ny

  GPUSOLVE_HD T* data() const { return ptr; }
  GPUSOLVE_HD T& operator()(std::size_t i, std::size_t j, std::size_t k) const {
    if constexpr (Check::bounds_check) {
      if (i >= nx || j >= ny || k >= nz) detail::bounds_violation(3, i, j, k, nx, ny, nz);
    }
    return ptr[(k * pitch_y + j) * pitch_x + i];
  }
};

static_assert(std::is_trivially_copyable_v<VectorD1View<float>>);
static_assert(std::is_trivially_copyable_v<VectorD2View<float>>);
static_assert(std::is_trivially_copyable_v<VectorD3View<float>>);

}  // namespace gpusolve
