// Contact models (thesis Eq. 6-8): how many impulse rows a contact has and how they are projected.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// A contact model is a compile-time policy with
//   static constexpr std::size_t rows;                       // impulse rows per contact
//   static constexpr bool friction;                          // tangents and mu are stored
//   template <class T> static void project(T* x, T mu);      // onto the admissible set
// Row 0 is always the normal impulse, rows 1 and 2 (if any) the tangential ones
// along the contact's t and o.

// Frictionless contacts: one row, x_n >= 0 (thesis Eq. 6).
struct Frictionless {
  static constexpr std::size_t rows = 1;
  static constexpr bool friction = false;
  template <class T>
  GPUSOLVE_HD static void project(T* x, T /*mu*/) {
    if (x[0] < T(0)) x[0] = T(0);  // a NaN stays NaN so that divergence is seen, not hidden
  }
};

// Pyramidal friction (thesis Eq. 7-8): x_n >= 0 and |x_t|, |x_o| <= mu x_n, each
// tangential row clamped on its own (a four-sided pyramid, not a cone).
struct PyramidFriction {
  static constexpr std::size_t rows = 3;
  static constexpr bool friction = true;
  template <class T>
  GPUSOLVE_HD static void project(T* x, T mu) {
    if (x[0] < T(0)) x[0] = T(0);
    const T lim = mu * x[0];
    for (std::size_t r = 1; r < 3; ++r) x[r] = x[r] > lim ? lim : (x[r] < -lim ? -lim : x[r]);
  }
};

}  // namespace gpusolve::rbd
