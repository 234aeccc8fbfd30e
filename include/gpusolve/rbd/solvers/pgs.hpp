// Projected Gauss-Seidel: the sequential reference solver on the host, built from
// the same per-contact functions and projection as the Jacobi solver.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

// Same contract as JacobiSolver::solve; one iteration is one sweep over the
// contacts in order, and the residual (contact_kernels.hpp) is the largest
// velocity change of that sweep; a diverging sweep is retried at a smaller omega
// like the Jacobi solver's. omega 0 (the default) is plain Gauss-Seidel, omega 1.
template <class T, class Model>
SolverStats<T> solve_gauss_seidel(Bodies<device::cpu, T>& bodies, Contacts<device::cpu, T, Model>& contacts,
                                  const SolverSettings<T>& s) {
  using BV = typename Bodies<device::cpu, T>::View;
  using CV = typename Contacts<device::cpu, T, Model>::View;
  s.validate();
  SolverStats<T> stats;
  const std::size_t nc = contacts.size();
  stats.contacts = nc;
  if (nc == 0) return stats;
  const BV b = bodies.view();
  const CV c = contacts.view();
  VectorD2<T, device_is<device::cpu>> rhs(nc, Model::rows);
  VectorD1<T, device_is<device::cpu>> residual(nc);
  const InverseBlocks<Model, BV, CV, T> blocks{b, c, nullptr, false};  // one point at a time: whole steps
  const CalcNextPhi<Model, BV, CV, T> phi{b, c, rhs.view(), T(1) / s.dt, s.correction};
  for (std::size_t i = 0; i < nc; ++i) blocks(i);
  ResidualCheck<device::cpu, T> check;
  auto attempt = [&](T omega, SolverStats<T>& st) {
    contacts.x.fill(T(0));
    ConvergenceMonitor<T> monitor(s, st);
    for (std::size_t it = 1;; ++it) {
      const bool measure = monitor.checks(it);
      const ResolveCollisions<Model, BV, CV, detail::DirectSink<BV, T>, T> resolve{
          b, c, rhs.view(), detail::DirectSink<BV, T>{b}, omega, measure, residual.view()};
      for (std::size_t i = 0; i < nc; ++i) {
        phi(i);
        resolve(i);
      }
      if (measure && monitor.stop(it, check(b, residual.view(), nc))) break;
    }
  };
  VelocitySnapshot<device::cpu, T> start;
  solve_relaxed(s, s.omega > 0 ? s.omega : T(1), b, start, stats, attempt);
  return stats;
}

}  // namespace gpusolve::rbd
