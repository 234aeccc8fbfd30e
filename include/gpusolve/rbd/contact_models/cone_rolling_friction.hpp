// The Coulomb cone with torsional and rolling resistance: six impulse rows.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contact_models/cone_friction.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"

namespace gpusolve::rbd {

// Rows 0-2 as ConeFriction (normal, t, o, linear impulses at the contact
// point); rows 3-5 angular impulses about n (spinning) and about t and o
// (rolling), acting on a and, opposite, on b. Projection: the cone, then
// |x_3| <= spin x_n and |(x_4, x_5)| <= roll x_n with the cone's x_n, the
// rolling and spinning friction of Tasora and Anitescu (2013, "A complementarity-
// based rolling friction model for rigid contacts", Meccanica 48) as Chrono's
// NSC contacts solve them with APGD. spin and roll are lengths: a resisting
// torque of at most spin N about the normal and roll N against rolling.
struct ConeRollingFriction {
  static constexpr std::size_t rows = 6, linear_rows = 3;
  static constexpr bool friction = true;
  template <class T>
  GPUSOLVE_HD static void project(T* x, const ContactLimits<T>& k) {
    ConeFriction::project(x, k);
    const T spin = k.spin * x[0];
    x[3] = x[3] > spin ? spin : (x[3] < -spin ? -spin : x[3]);
    ConeFriction::onto_disc(x[4], x[5], k.roll * x[0]);
  }
};

}  // namespace gpusolve::rbd
