// Pyramidal friction (thesis Eq. 7-8): each tangential row clamped on its own.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"

namespace gpusolve::rbd {

// x_n >= 0 and |x_t|, |x_o| <= mu x_n: a four-sided pyramid, not a cone. Its
// friction depends on the direction of sliding: along a diagonal of the pyramid
// the force reaches sqrt(2) mu N (ConeFriction does not).
struct PyramidFriction {
  static constexpr std::size_t rows = 3, linear_rows = 3;
  static constexpr bool friction = true;
  template <class T>
  GPUSOLVE_HD static void project(T* x, const ContactLimits<T>& k) {
    if (x[0] < T(0)) x[0] = T(0);
    const T lim = k.mu * x[0];
    for (std::size_t r = 1; r < 3; ++r) x[r] = x[r] > lim ? lim : (x[r] < -lim ? -lim : x[r]);
  }
};

}  // namespace gpusolve::rbd
