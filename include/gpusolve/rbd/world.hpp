// World: one rigid-body simulation on one backend: bodies, contacts, settings,
// and step() = collision detection + contact solve + integration.
#pragma once

#include <chrono>
#include <cstddef>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/statistics/accuracy.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "gpusolve/rbd/contact_models/contact_model.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"
#include "gpusolve/rbd/solvers/coloured_gauss_seidel.hpp"
#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/solvers/substepping.hpp"
#include "gpusolve/rbd/solvers/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"
#include "gpusolve/rbd/solvers/warm_start.hpp"

namespace gpusolve::rbd {

namespace detail {

// Waits until the backend finished the work queued on `stream` (timing per phase).
inline void finish(device::cpu, stream_t) {}
inline void finish(device::gpu, stream_t stream) {
#if GPUSOLVE_HAS_CUDART
  GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(stream));
#else
  (void)stream;
#endif
}

}  // namespace detail

// The bodies come from a host BodySet through a BodyManager (copied once at
// construction; later changes are announced to manager()). Everything in step()
// runs where the bodies live; the host is touched only by syncHost() and the
// statistics' scalars. Model: a contact model (contact_models/); Method: a
// solver's tag (solvers/solver.hpp: Jacobi<Strategy>, ColouredGaussSeidel, ...).
// The defaults are the atlas's best (README, "Choosing a method"): APGD with the
// per-body gather, at its default budget (50 iterations) faster per step than
// Jacobi and coloured Gauss-Seidel at equal penetration on the shared piles
// (below about 20 iterations plain Jacobi is cheaper), and the one method that
// converges on a 1:1000 mass-ratio column; and the isotropic cone.
template <class Device, class T = float, class Model = ConeFriction, class Method = AcceleratedJacobi<Gather>>
class World {
 public:
  using solver_type = solver_t<Method, Device, T, Model>;
  static_assert(is_solver<solver_type, Device, T, Model>::value,
                "World: Method::solver must model the Solver concept (gpusolve/rbd/solvers/solver.hpp)");

  World(BodySet<T>& set, const SolverSettings<T>& settings, stream_t stream = stream_t{})
      : manager_(set), stream_(stream) {
    set_settings(settings);
    manager_.syncDeviceFull(stream_);
  }

  // Throws InvalidArgumentError naming the field before anything changes.
  void set_settings(const SolverSettings<T>& s) {
    s.validate();
    settings_ = s;
  }
  const SolverSettings<T>& settings() const { return settings_; }

  StepStats<T> step() {
    using Clock = std::chrono::steady_clock;
    auto& bodies = manager_.device();
    const SolverSettings<T>& s = settings_;
    const math::Vector3<T> g(s.gravity[0], s.gravity[1], s.gravity[2]);
    StepStats<T> st;

    const auto t0 = Clock::now();
    detection_.detect(bodies, contacts_, s.margin, s.friction, stream_);
    detail::finish(Device{}, stream_);
    const auto t1 = Clock::now();
    constexpr bool own_integration = !integrates<solver_type>::value;  // else the solver moves the bodies
    if (own_integration) apply_forces(bodies, s.dt, g, stream_);  // the LCP sees v + dt M^-1 f_ext (thesis Eq. 6)
    const bool warm = s.warm_start > 0;
    if (warm) warm_.carry(contacts_.view(), s.warm_start, stream_);
    st.solver = solver_.solve(bodies, contacts_, s, stream_, warm);
    if (warm)
      warm_.remember(contacts_.view(), stream_);
    else
      warm_.forget();
    detail::finish(Device{}, stream_);
    const auto t2 = Clock::now();
    if (own_integration) move(bodies, s.dt, stream_);
    detail::finish(Device{}, stream_);
    const auto t3 = Clock::now();

    using BV = typename Bodies<Device, T>::View;
    const BV b = bodies.view();
    st.max_penetration = max_relative_penetration<Device, T>(b, contacts_.view(), stream_);
    st.kinetic_energy = kinetic_energy<Device, BV, T>(b, stream_);
    st.potential_energy = potential_energy<Device, BV, T>(b, g, stream_);
    using Sec = std::chrono::duration<double>;
    st.time_detection = Sec(t1 - t0).count();
    st.time_solve = Sec(t2 - t1).count();
    st.time_integration = Sec(t3 - t2).count();
    return st;
  }

  // Copies positions, orientations and velocities back into the BodySet.
  void syncHost() { manager_.syncHost(stream_); }

  Bodies<Device, T>& bodies() { return manager_.device(); }
  Contacts<Device, T, Model>& contacts() { return contacts_; }
  BodyManager<Device, T>& manager() { return manager_; }

 private:
  BodyManager<Device, T> manager_;
  stream_t stream_;
  SolverSettings<T> settings_;
  CollisionDetection<Device, T> detection_;
  Contacts<Device, T, Model> contacts_;
  solver_type solver_;
  WarmStart<Device, T, Model> warm_;  // the previous step's impulses (settings.warm_start)
};

}  // namespace gpusolve::rbd
