// ContactSolverBase: the state and the first steps every projected contact solver shares.
#pragma once

#include <cstddef>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

// Scratch kept between solves (each contact's residual, the start velocities
// for a retry, the residual reduction) and begin(): validate
// the settings, size the scratch and compute each contact's inverse block.
template <class Device, class T, class Model>
class ContactSolverBase {
 public:
  using BodyStore = Bodies<Device, T>;
  using ContactStore = Contacts<Device, T, Model>;
  using BV = typename BodyStore::View;
  using CV = typename ContactStore::View;

 protected:
  // Returns false when there is nothing to solve (no contacts: converged in
  // zero iterations). Throws InvalidArgumentError for bad settings.
  bool begin(const BV& b, const CV& c, const SolverSettings<T>& s, SolverStats<T>& stats, stream_t stream) {
    if (!prepare(c, s, stats)) return false;
    launch(Device{}, c.size(), inverse_blocks(b, c), stream);  // independent of velocities: once
    return true;
  }
  // begin() but the inverse blocks, for a solver that runs inverse_blocks() itself.
  // Sizes by the contacts' bound (Contacts::View::bound).
  bool prepare(const CV& c, const SolverSettings<T>& s, SolverStats<T>& stats) {
    s.validate();
    stats.contacts = c.bound();
    if (c.bound() == 0) return false;
    gpusolve::detail::ensure_size(residual_, c.bound());
    return true;
  }
  InverseBlocks<Model, BV, CV, T> inverse_blocks(const BV& b, const CV& c) const { return {b, c}; }
  // The largest residual of this iteration's contacts (+inf for a non-finite
  // velocity), over the ranks where an `exchange` shares the solve.
  T residual(const BV& b, std::size_t contacts, stream_t stream, BodyExchange<T>* exchange = nullptr) {
    return check_(b, residual_.view(), contacts, stream, exchange);
  }
  // Its terms, for a program that takes their maximum itself (over max(contacts' bound, bodies) indices).
  detail::ResidualOrNotFinite<BV, T> residual_terms(const BV& b, const CV& c) {
    return {b, residual_.view(), c.count};
  }

  VectorD1<T, device_is<Device>> residual_;
  VelocitySnapshot<Device, T> start_;

 private:
  ResidualCheck<Device, T> check_;
};

}  // namespace gpusolve::rbd
