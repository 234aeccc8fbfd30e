// Isotropic (Coulomb cone) friction: the tangential impulse lies in a disc.
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// x_n >= 0 and |(x_t, x_o)| <= mu x_n. The projection keeps the direction of
// the tangential impulse and shortens it onto the disc's rim, the projection
// used by the cone-complementarity solvers (Anitescu and Tasora 2010; Mazhar et
// al. 2015, Chrono): the friction force of a sliding contact is mu N whatever
// the direction of sliding, unlike PyramidFriction's sqrt(2) mu N on a diagonal.
struct ConeFriction {
  static constexpr std::size_t rows = 3;
  static constexpr bool friction = true;
  template <class T>
  GPUSOLVE_HD static void project(T* x, T mu) {
    if (x[0] < T(0)) x[0] = T(0);
    const T lim = mu * x[0];
    const T len = std::sqrt(x[1] * x[1] + x[2] * x[2]);
    if (len > lim) {  // false for NaN: it stays, and divergence is seen
      const T s = len > T(0) ? lim / len : T(0);
      x[1] *= s;
      x[2] *= s;
    }
  }
};

}  // namespace gpusolve::rbd
