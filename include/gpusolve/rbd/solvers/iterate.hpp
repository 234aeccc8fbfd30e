// The iterate a Jacobi-family iteration starts from, as its two kernels see it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd::detail {

// An Iterate tells the contact kernel (JacobiContact) and the per-body sum
// (the accumulators' to_bodies) where the iteration starts and what it keeps:
//  - start(c, i, x, y): contact i's impulse x and the point y its projected
//    update starts from;
//  - velocity(b, k, v, w): body k's velocities its contacts' errors are computed from;
//  - store(c, i, e, x0, x): contact i's new impulse x, computed from error e,
//    x0 being the impulse start() gave (so it is not loaded again after the
//    update's stores);
//  - add(b, k, sv, sw): body k's new velocities, given its contacts' summed changes;
//  - bodies_first: whether JacobiContact loads the contact's bodies (masses,
//    inertias) before the error rather than after the impulse. Early, they
//    share the velocities' round trip to memory instead of taking one of their
//    own; an extrapolating iterate, with loads of its own, keeps them late
//    (docs/tuning/solve.md).
// CurrentIterate is the plain one: the impulses and velocities as they are.
// A momentum method extrapolates instead (momentum.hpp, ExtrapolatedIterate),
// without a pass of its own over impulses and velocities.
template <class T>
struct CurrentIterate {
  static constexpr bool bodies_first = true;
  template <class CV, std::size_t R>
  GPUSOLVE_HD void start(const CV& c, std::size_t i, T (&x)[R], T (&y)[R]) const {
    for (std::size_t r = 0; r < R; ++r) x[r] = y[r] = c.x(i, r);
  }
  template <class BV>
  GPUSOLVE_HD void velocity(const BV& b, std::uint32_t k, math::Vector3<T>& v, math::Vector3<T>& w) const {
    v = math::Vector3<T>(b.v(k, 0), b.v(k, 1), b.v(k, 2));
    w = math::Vector3<T>(b.w(k, 0), b.w(k, 1), b.w(k, 2));
  }
  template <class CV, std::size_t R>
  GPUSOLVE_HD void store(const CV& c, std::size_t i, const T (&)[R], const T (&)[R], const T (&x)[R]) const {
    for (std::size_t r = 0; r < R; ++r) c.x(i, r) = x[r];
  }
  // All six loads before the first store: the compiler may not move a load
  // past a store (the views might alias), and one after each store would wait
  // a memory round trip each.
  template <class BV>
  GPUSOLVE_HD void add(const BV& b, std::size_t k, const T (&sv)[3], const T (&sw)[3]) const {
    T v[3], w[3];
    for (std::size_t c = 0; c < 3; ++c) v[c] = b.v(k, c), w[c] = b.w(k, c);
    for (std::size_t c = 0; c < 3; ++c) b.v(k, c) = v[c] + sv[c], b.w(k, c) = w[c] + sw[c];
  }
};

}  // namespace gpusolve::rbd::detail
