// SolverSettings: the time step and the Jacobi solver's parameters, validated before use.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd {

template <class T>
struct SolverSettings {
  T dt = T(0.0025);            // time step (s)
  // Relaxation of the projected update, in [0, 2); 0 takes the method's own
  // default (Jacobi 0.5, under-relaxed as in thesis 5.2, which used 0.2 to 0.7;
  // APGD 0.3; Gauss-Seidel 1).
  T omega = T(0);
  T tolerance = T(5e-3);       // stop when the LCP residual (m/s, see contact_kernels.hpp) is below
  // 50: on the shared 100 000-sphere pile (bench/atlas.cu, README) 50 APGD
  // iterations with warm start hold the penetration at 0.10% of the radius in
  // 5.7 to 6.0 ms per step on an H200, where the tolerance alone ran Jacobi to its old
  // cap of 2 000 (64 ms, 2.7%); a scene that needs converged solves raises it.
  std::size_t max_iterations = 50;
  std::size_t check_every = 50;      // iterations between residual checks (thesis: 50)
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
  T gravity[3] = {T(0), T(0), T(-9.81)};
  // Contacts are kept while the gap is below this (m). 0.1 (a tenth of a unit
  // radius): a sphere falling at up to ~0.1 m per step is caught before it sinks
  // in; on the shared 10 000-sphere pile it cut the penetration at 10 Jacobi
  // iterations from 0.98% to 0.23% (bench/results/atlas). Scale it with the scene.
  T margin = T(0.1);
  T correction = T(0.2);       // fraction of a penetration removed per step, in (0, 1]
  T friction = T(0.5);         // friction coefficient of every contact (models with friction)
  // World::step starts each persisting contact (same body pair as in the last
  // step) from this fraction of its last impulse, in [0, 1] (0: every solve
  // starts from zero impulses). 0.8: on a boxed pile of 360 spheres (CPU, float,
  // defaults otherwise) 136 iterations per step on average against 194 cold and
  // 182 at 1, which overshoots and made solves diverge and retry.
  T warm_start = T(0.8);
  // Substeps per time step of the substepping method (solvers/substepping.hpp);
  // the other methods ignore it. max_iterations is shared among the substeps.
  std::size_t substeps = 4;
  bool throw_on_divergence = false;  // solve() throws DivergenceError instead of reporting it
  // GPU: collision detection runs as one CUDA graph, captured once and launched
  // again while the bodies, the contacts' storage, the margin and the friction
  // stay (CollisionDetection::set_graphs; its kernels read the step's counts
  // from device memory, so a contact count that changes does not recapture).
  // On the shared pile on an H200 (bench/step.cu, README) it took 0.03 to 0.05
  // ms off a step at the defaults from 1 000 to 100 000 spheres. The CPU ignores it.
  bool detection_graph = true;
  // GPU: where the persistent kernel is not used (persistent_max_contacts), the
  // Jacobi-family solvers' runs of iterations between two residual checks are
  // captured into CUDA graphs, updated in place and replayed
  // (detail/graph_replay.hpp): the same kernels in the same order. Off by
  // default: a run's arguments change every step (the contact count), and
  // capturing anew cost more than the launches it saved (on the 1 000 000-sphere
  // pile on an H200, 16.3 against 15.9 ms per step at the defaults). The CPU ignores it.
  bool graphs = false;
  // GPU: the Jacobi-family solvers (and substepping through them) run each run
  // of iterations between two residual checks as one cooperative kernel, the
  // phases of an iteration separated by grid-wide barriers
  // (detail/persistent_loop.hpp; the same functors as the launches), when the
  // step has at most this many contacts; above it, or at 0, a launch per phase.
  // It takes precedence over `graphs`. On the shared pile on an H200
  // (bench/step.cu, README) the kernel made a step at the defaults 1.4 to 2.1
  // times faster up to 281 000 contacts, 13% faster at 529 000, 2% slower at
  // 1.02 million and 10% slower at 1.67 million, where an iteration is bound by
  // bandwidth, not by launches. The CPU ignores it.
  std::size_t persistent_max_contacts = 1000000;
  // GPU (sm_90 and later): a persistent kernel whose grid fits in one
  // thread-block cluster (at most 16 blocks of 256 threads: about 4 000
  // contacts) runs as that cluster, its phases separated by the cluster's
  // hardware barrier instead of the grid-wide barrier through global memory;
  // the same blocks, the same arithmetic in the same order. The CPU ignores it.
  bool persistent_clusters = true;

  // Throws InvalidArgumentError naming the first offending field.
  void validate() const {
    auto bad = [](const char* field, const std::string& why) {
      std::ostringstream os;
      os << "gpusolve: solver setting `" << field << "` " << why;
      throw InvalidArgumentError(os.str());
    };
    if (!(dt > 0) || !std::isfinite(dt)) bad("dt", "must be positive and finite");
    if (!(omega >= 0 && omega < 2)) bad("omega", "must lie in [0, 2) (0: the method's default)");
    if (!(tolerance > 0) || !std::isfinite(tolerance)) bad("tolerance", "must be positive and finite");
    if (max_iterations == 0) bad("max_iterations", "must be at least 1");
    if (check_every == 0) bad("check_every", "must be at least 1");
    if (!(divergence_growth >= 1)) bad("divergence_growth", "must be at least 1");
    if (!(retry_omega_factor > 0 && retry_omega_factor < 1)) bad("retry_omega_factor", "must lie in (0, 1)");
    // The last retry's omega must still be a normal positive number of type T.
    // Every method's default omega is at least 0.3.
    if (!((omega > 0 ? omega : T(0.3)) * std::pow(retry_omega_factor, T(max_retries)) >= std::numeric_limits<T>::min()))
      bad("max_retries", "makes omega * retry_omega_factor^max_retries underflow");
    for (T g : gravity)
      if (!std::isfinite(g)) bad("gravity", "must be finite");
    if (!(margin >= 0) || !std::isfinite(margin)) bad("margin", "must be non-negative and finite");
    if (!(correction > 0 && correction <= 1)) bad("correction", "must lie in (0, 1]");
    if (!(friction >= 0) || !std::isfinite(friction)) bad("friction", "must be non-negative and finite");
    if (!(warm_start >= 0 && warm_start <= 1)) bad("warm_start", "must lie in [0, 1]");
    if (substeps == 0) bad("substeps", "must be at least 1");
  }
};

}  // namespace gpusolve::rbd
