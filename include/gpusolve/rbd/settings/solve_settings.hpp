// SolveSettings: the numerics of a contact solve: relaxation, the stopping and
// divergence rules, retries at a smaller relaxation, the warm start, substeps.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "gpusolve/rbd/settings/setting_error.hpp"

namespace gpusolve::rbd {

template <class T>
struct SolveSettings {
  // Relaxation of the projected update, in [0, 2); 0 takes the method's own
  // default (Jacobi 0.5, under-relaxed as in thesis 5.2, which used 0.2 to 0.7;
  // APGD 0.3; Gauss-Seidel 1).
  T omega = T(0);
  T tolerance = T(5e-3);  // stop when the LCP residual (m/s, see contact_kernels.hpp) is below
  // The iteration budget of a step; a scene that needs converged solves raises
  // it (docs/tuning/solve.md: the budget against penetration).
  std::size_t max_iterations = 50;
  // Iterations between residual checks; 0 takes the method's own: every 10
  // (ConvergenceRule), so that a resting scene stops early, and every 50 for
  // AcceleratedCG (the thesis's; docs/tuning/solve.md).
  std::size_t check_every = 0;
  // Divergence: the residual grew at `divergence_checks` checks in a row (0: off)
  // and is `divergence_growth` times the smallest residual seen in the solve.
  // Both together, because a converging projected Jacobi iteration fluctuates.
  std::size_t divergence_checks = 3;
  T divergence_growth = T(10);
  // Adaptive under-relaxation (thesis 5.2 leaves it as future work): a solve that
  // diverges restarts from the velocities it began with, omega multiplied by
  // `retry_omega_factor`, at most `max_retries` times (0: off); only when the last
  // attempt diverges too is the step reported diverged.
  std::size_t max_retries = 3;
  T retry_omega_factor = T(0.5);
  // World::step starts each persisting contact (same body pair as in the last
  // step) from this fraction of its last impulse, in [0, 1] (0: every solve
  // starts from zero impulses); a full impulse overshoots (docs/tuning/solve.md).
  T warm_start = T(0.8);
  // Substeps per time step of the substepping method (solvers/substepping.hpp);
  // the other methods ignore it. max_iterations is shared among the substeps.
  std::size_t substeps = 4;
  bool throw_on_divergence = false;  // solve() throws DivergenceError instead of reporting it

  // Throws InvalidArgumentError naming the first offending field.
  void validate() const {
    using detail::bad_setting;
    if (!(omega >= 0 && omega < 2)) bad_setting("omega", "must lie in [0, 2) (0: the method's default)");
    if (!(tolerance > 0) || !std::isfinite(tolerance)) bad_setting("tolerance", "must be positive and finite");
    if (max_iterations == 0) bad_setting("max_iterations", "must be at least 1");
    if (!(divergence_growth >= 1)) bad_setting("divergence_growth", "must be at least 1");
    if (!(retry_omega_factor > 0 && retry_omega_factor < 1)) bad_setting("retry_omega_factor", "must lie in (0, 1)");
    // The last retry's omega must still be a normal positive number of type T.
    // Every method's default omega is at least 0.3.
    if (!((omega > 0 ? omega : T(0.3)) * std::pow(retry_omega_factor, T(max_retries)) >= std::numeric_limits<T>::min()))
      bad_setting("max_retries", "makes omega * retry_omega_factor^max_retries underflow");
    if (!(warm_start >= 0 && warm_start <= 1)) bad_setting("warm_start", "must lie in [0, 1]");
    if (substeps == 0) bad_setting("substeps", "must be at least 1");
  }
};

}  // namespace gpusolve::rbd
