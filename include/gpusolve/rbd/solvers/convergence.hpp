// The residual check shared by every solver: the measured LCP residual and
// ConvergenceMonitor, the stopping and divergence rules fed with it.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"
#include "gpusolve/rbd/solvers/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// The one reduction of a residual check, over max(contacts, bodies) indices:
// residual[i] for a contact i, +inf where body i's velocity is not finite (so a
// NaN velocity reads as divergence even on a body without contacts), else 0.
template <class BV, class T>
struct ResidualOrNotFinite {
  BV b;
  VectorD1View<T> residual;
  std::size_t contacts;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    if (i < b.size())
      for (std::size_t c = 0; c < 3; ++c)
        if (!(std::fabs(b.v(i, c)) <= std::numeric_limits<T>::max()) ||
            !(std::fabs(b.w(i, c)) <= std::numeric_limits<T>::max()))
          return std::numeric_limits<T>::infinity();
    return i < contacts ? residual[i] : T(0);
  }
};

}  // namespace detail

// The measured LCP residual of a solver: the largest residual of the contacts
// (ResolveCollisions with measure set), +inf when any body velocity is not
// finite. One reduction per check; its scratch is kept between checks.
template <class Device, class T>
class ResidualCheck {
 public:
  template <class BV>
  T operator()(const BV& b, VectorD1View<T> residual, std::size_t contacts, stream_t stream = stream_t{}) {
    const std::size_t n = contacts > b.size() ? contacts : b.size();
    return reduce_(n, detail::ResidualOrNotFinite<BV, T>{b, residual, contacts}, T(0), stream);
  }
  std::size_t scratch_bytes() const { return reduce_.scratch_bytes(); }

 private:
  MaxReducer<Device, T> reduce_;
};

template <class T>
class ConvergenceMonitor {
 public:
  ConvergenceMonitor(const SolverSettings<T>& s, SolverStats<T>& stats) : s_(s), stats_(stats) {}

  // Whether iteration `it` (1-based) measures the residual: every check_every
  // iterations and always the last one, so the final residual is known.
  bool checks(std::size_t it) const { return it % s_.check_every == 0 || it == s_.max_iterations; }
  // The first iteration from `it` on that checks.
  std::size_t next_check(std::size_t it) const {
    const std::size_t k = (it + s_.check_every - 1) / s_.check_every * s_.check_every;
    return k < s_.max_iterations ? k : s_.max_iterations;
  }

  // Records the residual after iteration `it`; returns true when the solve must stop.
  // Diverged: the residual is not finite (NaN/inf in impulses or velocities), or it
  // grew at `divergence_checks` checks in a row to `divergence_growth` times its
  // smallest value so far. Converged: below the tolerance.
  bool stop(std::size_t it, T residual) {
    stats_.iterations = it;
    stats_.residuals.push_back(residual);
    stats_.checked_at.push_back(it);
    if (!(residual <= std::numeric_limits<T>::max())) return finish(SolverStatus::diverged);
    if (residual < s_.tolerance) return finish(SolverStatus::converged);
    growing_ = residual > previous_ ? growing_ + 1 : 0;
    previous_ = residual;
    smallest_ = residual < smallest_ ? residual : smallest_;
    if (s_.divergence_checks != 0 && growing_ >= s_.divergence_checks &&
        residual > s_.divergence_growth * smallest_)
      return finish(SolverStatus::diverged);
    if (it >= s_.max_iterations) return finish(SolverStatus::max_iterations);
    return false;
  }

 private:
  bool finish(SolverStatus st) {
    stats_.status = st;
    return true;
  }
  const SolverSettings<T>& s_;
  SolverStats<T>& stats_;
  T previous_ = std::numeric_limits<T>::infinity();
  T smallest_ = std::numeric_limits<T>::infinity();
  std::size_t growing_ = 0;
};

}  // namespace gpusolve::rbd
