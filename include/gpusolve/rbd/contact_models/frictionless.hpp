// Frictionless contacts: one impulse row, the normal one (thesis Eq. 6).
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// x_n >= 0. The cheapest model: 1 row, no tangents or friction coefficient stored.
struct Frictionless {
  static constexpr std::size_t rows = 1;
  static constexpr bool friction = false;
  template <class T>
  GPUSOLVE_HD static void project(T* x, T /*mu*/) {
    if (x[0] < T(0)) x[0] = T(0);  // a NaN stays NaN so that divergence is seen, not hidden
  }
};

}  // namespace gpusolve::rbd
