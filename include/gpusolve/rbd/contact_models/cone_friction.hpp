// Isotropic (Coulomb cone) friction: the tangential impulse lies in a disc.
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"

namespace gpusolve::rbd {

// x_n >= 0 and |(x_t, x_o)| <= mu x_n. The projection keeps the direction of
// the tangential impulse and shortens it onto the disc's rim, the projection
// used by the cone-complementarity solvers (Anitescu and Tasora 2010; Mazhar et
// al. 2015, Chrono): the friction force of a sliding contact is mu N whatever
// the direction of sliding, unlike PyramidFriction's sqrt(2) mu N on a diagonal.
struct ConeFriction {
  static constexpr std::size_t rows = 3, linear_rows = 3;
  static constexpr bool friction = true;
  template <class T>
  GPUSOLVE_HD static void project(T* x, const ContactLimits<T>& k) {
    if (x[0] < T(0)) x[0] = T(0);
    onto_disc(x[1], x[2], k.mu * x[0]);
  }
  // (u, v) shortened onto the disc of radius lim where it lies outside.
  template <class T>
  GPUSOLVE_HD static void onto_disc(T& u, T& v, T lim) {
    const T len = std::sqrt(u * u + v * v);
    if (len > lim) {  // false for NaN: it stays, and divergence is seen
      const T s = len > T(0) ? lim / len : T(0);
      u *= s;
      v *= s;
    }
  }
};

}  // namespace gpusolve::rbd
