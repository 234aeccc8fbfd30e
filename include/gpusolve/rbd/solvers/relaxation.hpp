// Adaptive under-relaxation (thesis 5.2 leaves it as future work): a solve that
// diverges restarts from the velocities it began with at a smaller omega.
#pragma once

#include <cstddef>

#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// Copies the bodies' v and w into the saved copy, or back with `restore`.
template <class BV, class T>
struct CopyVelocities {
  BV b;
  VectorD2View<T> v, w;  // bodies x 3
  bool restore;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    for (std::size_t c = 0; c < 3; ++c) {
      if (restore)
        b.v(k, c) = v(k, c), b.w(k, c) = w(k, c);
      else
        v(k, c) = b.v(k, c), w(k, c) = b.w(k, c);
    }
  }
};

}  // namespace detail

// The bodies' velocities at the start of a solve, kept on the bodies' backend
// (no host round trip). Storage only grows. A solver may take the copy in a
// phase of its own first kernel instead of a launch of its own: reserve(b),
// then run saver(b) over the bodies.
template <class Device, class T>
class VelocitySnapshot {
 public:
  template <class BV>
  void save(const BV& b, stream_t stream = stream_t{}) {
    reserve(b);
    copy(b, false, stream);
  }
  template <class BV>
  void reserve(const BV& b) {
    gpusolve::detail::ensure_size(v_, b.size(), 3), gpusolve::detail::ensure_size(w_, b.size(), 3);
  }
  template <class BV>
  detail::CopyVelocities<BV, T> saver(const BV& b) {
    return {b, v_.view(), w_.view(), false};
  }
  template <class BV>
  void restore(const BV& b, stream_t stream = stream_t{}) {
    copy(b, true, stream);
  }

 private:
  template <class BV>
  void copy(const BV& b, bool restore, stream_t stream) {
    launch(Device{}, b.size(), detail::CopyVelocities<BV, T>{b, v_.view(), w_.view(), restore}, stream);
  }
  VectorD2<T, device_is<Device>> v_, w_;
};

// Throws DivergenceError when the solve's last attempt diverged and the settings ask for it.
template <class T>
void report_divergence(const SolverSettings<T>& s, const SolverStats<T>& stats) {
  if (stats.status == SolverStatus::diverged && s.throw_on_divergence)
    throw DivergenceError(stats.iterations, double(stats.residual()), double(stats.omega), stats.retries);
}

// Runs attempt(omega, stats) from `omega`, one solve from the bodies' current velocities
// (its starting impulses are its own choice; stats.retries says which attempt
// it is) that sets stats.status, iterations and the residual history. While an attempt diverges and s.max_retries allows, restores the
// velocities saved before the first attempt, multiplies omega by
// s.retry_omega_factor and runs it again. stats then holds the last attempt,
// the omega it used, the number of retries and the iterations of all attempts.
// Throws DivergenceError when the last attempt diverged and the settings ask for it.
// With `first_attempt_saves` the first attempt takes the copy itself
// (VelocitySnapshot::saver, before it changes a velocity); storage is reserved here.
template <class Device, class T, class BV, class Attempt>
void solve_relaxed(const SolverSettings<T>& s, T omega, const BV& b, VelocitySnapshot<Device, T>& start,
                   SolverStats<T>& stats, Attempt&& attempt, stream_t stream = stream_t{},
                   bool first_attempt_saves = false) {
  if (s.max_retries > 0) {
    if (first_attempt_saves)
      start.reserve(b);
    else
      start.save(b, stream);
  }
  stats.omega = omega;
  for (;;) {
    stats.residuals.clear();
    stats.checked_at.clear();
    attempt(stats.omega, stats);
    stats.total_iterations += stats.iterations;
    if (stats.status != SolverStatus::diverged || stats.retries == s.max_retries) break;
    start.restore(b, stream);
    stats.omega *= s.retry_omega_factor;
    ++stats.retries;
  }
  report_divergence(s, stats);
}

}  // namespace gpusolve::rbd
