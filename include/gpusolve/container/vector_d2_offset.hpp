// Precomputed row offsets of a VectorD2 with N rows (thesis 4.2.1): element
// (i, j) lives at linear offset i + row(j). Vectors of one length share one.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve {

template <std::size_t N>
struct VectorD2Offset {
  std::size_t row[N] = {};

  VectorD2Offset() = default;
  GPUSOLVE_HD explicit VectorD2Offset(std::size_t pitch) {
    for (std::size_t j = 0; j < N; ++j) row[j] = j * pitch;
  }
  template <class View>
  GPUSOLVE_HD static VectorD2Offset of(const View& v) {
    return VectorD2Offset(v.pitch);
  }

  GPUSOLVE_HD std::size_t operator()(std::size_t i, std::size_t j) const { return i + row[j]; }
  static constexpr std::size_t rows = N;
};

}  // namespace gpusolve
