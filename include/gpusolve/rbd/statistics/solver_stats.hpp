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
// after iteration checked_at[k]; the last entry is the final residual. With
// adaptive under-relaxation (SolverSettings::max_retries) status, iterations and
// the residual history are those of the last attempt, the one whose velocities
// the solve returned; total_iterations counts the discarded attempts too.
template <class T>
struct SolverStats {
  SolverStatus status = SolverStatus::converged;
  std::size_t contacts = 0;
  std::size_t iterations = 0;
  std::size_t total_iterations = 0;  // every attempt's iterations: the work done
  T omega = 0;                       // the under-relaxation of the last attempt
  std::size_t retries = 0;           // attempts restarted after a divergence
  std::size_t reduction_passes = 0;  // UpdateCache only: ceil(log2 c_max)
  std::size_t colours = 0;           // ColouredGaussSeidel only: colours of the step's contacts
  std::vector<T> residuals;
  std::vector<std::size_t> checked_at;
  T residual() const { return residuals.empty() ? T(0) : residuals.back(); }
};

// One time step of a World: the solve, the accuracy figures and the time
// (seconds) of each phase, measured on the backend's stream when the World's
// phase timing is on (World::set_phase_timing), else zero.
template <class T>
struct StepStats {
  SolverStats<T> solver;
  T max_penetration = 0;  // largest max(0, -gap) / (smaller feature_size of the pair) over contacts
  T kinetic_energy = 0;
  T potential_energy = 0;  // -sum m g.x, zero at the origin
  double time_detection = 0, time_solve = 0;
  double time_integration = 0;  // the move, with the warm start's memory and the figures (one pass)
  T energy() const { return kinetic_energy + potential_energy; }
};

// Thrown by a solve whose settings ask for it (throw_on_divergence) when it
// diverged, after its retries (if any) diverged too.
class DivergenceError : public Error {
 public:
  DivergenceError(std::size_t iteration, double residual, double omega, std::size_t retries)
      : Error(message(iteration, residual, omega, retries)),
        iteration_(iteration),
        residual_(residual),
        omega_(omega),
        retries_(retries) {}
  std::size_t iteration() const noexcept { return iteration_; }
  double residual() const noexcept { return residual_; }
  double omega() const noexcept { return omega_; }
  std::size_t retries() const noexcept { return retries_; }

 private:
  static std::string message(std::size_t it, double r, double omega, std::size_t retries) {
    std::ostringstream os;
    os << "gpusolve: the contact solver diverged at iteration " << it << " (residual " << r << ") with omega "
       << omega << " after " << retries << " retr" << (retries == 1 ? "y" : "ies")
       << "; lower omega or the time step, or allow more retries";
    return os.str();
  }
  std::size_t iteration_;
  double residual_;
  double omega_;
  std::size_t retries_;
};

}  // namespace gpusolve::rbd
