// Frictionless contacts: one impulse row, the normal one (thesis Eq. 6).
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"

namespace gpusolve::rbd {

// x_n >= 0. The cheapest model: 1 row, no tangents or friction coefficient stored.
struct Frictionless {
  static constexpr std::size_t rows = 1, linear_rows = 1;
  static constexpr bool friction = false;
  template <class T>
  GPUSOLVE_HD static void project(T* x, const ContactLimits<T>&) {
    if (x[0] < T(0)) x[0] = T(0);  // a NaN stays NaN so that divergence is seen, not hidden
  }
};

}  // namespace gpusolve::rbd
