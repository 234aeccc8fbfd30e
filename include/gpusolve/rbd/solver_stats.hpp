// Per-step statistics of the solver and the world: how the solve ended, its
// residual history, accuracy figures and wall time per phase; DivergenceError.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd {

enum class SolverStatus {
  converged,       // the residual fell below the tolerance
  max_iterations,  // stopped at max_iterations with the residual above the tolerance
  diverged,        // NaN/inf in impulses or velocities, or the residual kept growing
};

inline const char* to_string(SolverStatus s) {
  switch (s) {
    case SolverStatus::converged: return "converged";
    case SolverStatus::max_iterations: return "max_iterations";
    default: return "diverged";
  }
}

// One solve. residuals[k] is the LCP residual (contact_kernels.hpp) measured
// after iteration checked_at[k]; the last entry is the final residual.
template <class T>
struct SolverStats {
  SolverStatus status = SolverStatus::converged;
  std::size_t contacts = 0;
  std::size_t iterations = 0;
  std::size_t reduction_passes = 0;  // UpdateCache only: ceil(log2 c_max)
  std::vector<T> residuals;
  std::vector<std::size_t> checked_at;
  T residual() const { return residuals.empty() ? T(0) : residuals.back(); }
};

// One time step of a World: the solve, the accuracy figures and the wall time
// (seconds) of each phase, measured after the backend finished it.
template <class T>
struct StepStats {
  SolverStats<T> solver;
  T max_penetration = 0;  // largest max(0, -gap) / (smaller radius of the pair) over contacts
  T kinetic_energy = 0;
  T potential_energy = 0;  // -sum m g.x, zero at the origin
  double time_detection = 0, time_solve = 0, time_integration = 0;
  T energy() const { return kinetic_energy + potential_energy; }
};

// Thrown by a solve whose settings ask for it (throw_on_divergence) when it diverged.
class DivergenceError : public Error {
 public:
  DivergenceError(std::size_t iteration, double residual)
      : Error(message(iteration, residual)), iteration_(iteration), residual_(residual) {}
  std::size_t iteration() const noexcept { return iteration_; }
  double residual() const noexcept { return residual_; }

 private:
  static std::string message(std::size_t it, double r) {
    std::ostringstream os;
    os << "gpusolve: the contact solver diverged at iteration " << it << " (residual " << r
       << "); lower omega or the time step";
    return os.str();
  }
  std::size_t iteration_;
  double residual_;
};

}  // namespace gpusolve::rbd
