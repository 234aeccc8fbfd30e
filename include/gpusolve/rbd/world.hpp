// World: one rigid-body simulation on one backend: bodies, contacts, settings,
// and step() = collision detection + contact solve + integration.
#pragma once

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
#include "gpusolve/rbd/detail/device_algorithms.hpp"
#include "gpusolve/rbd/detail/stream_marks.hpp"
#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/memory/cuda_host_allocator.hpp"
#include "gpusolve/memory/standard_allocator.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"
#include "gpusolve/rbd/solvers/accelerated_cg.hpp"
#include "gpusolve/rbd/solvers/coloured_gauss_seidel.hpp"
#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/solvers/substepping.hpp"
#include "gpusolve/rbd/solvers/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"
#include "gpusolve/rbd/solvers/warm_start.hpp"

namespace gpusolve::rbd {

namespace detail {
// The end of a step for index i: body i's move and contact i's impulse kept
// for the next step's warm start (World::queue_step runs it with the figures).
template <class Move, class Remember>
struct StepEnd {
  Move move;
  Remember remember;
  std::size_t bodies, remembered;  // WarmStart::remembered()
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (i < bodies) move(i);
    if (i < remembered) remember(i);
  }
};
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

  // Runs one step and returns its statistics (waits for them).
  StepStats<T> step() {
    advance(1);
    return latest_stats();
  }

  // Queues `steps` steps. The host waits only where the step's sizes need it
  // (the contact count after detection) and, on the solver's launched path or
  // where a divergence must throw, for the solver's checks; never for timing or
  // statistics. Under the persistent kernel the solver's verdict is read with
  // the step's statistics. Throws NonFiniteStateError naming
  // the body and the step when a body's state holds a NaN or infinity: that
  // step is not taken and no body changes.
  void advance(std::size_t steps = 1) {
    for (std::size_t k = 0; k < steps; ++k) queue_step();
  }

  // Statistics of the last step queued; waits until the backend finished it.
  StepStats<T> latest_stats() { return steps_ == 0 ? StepStats<T>{} : stats_of(current_); }
  // Statistics of the step before it: ready without a wait once a later step
  // was queued (its detection waited for the device). Zero before two steps.
  StepStats<T> previous_stats() { return steps_ < 2 ? StepStats<T>{} : stats_of(1 - current_); }
  std::size_t steps_queued() const { return steps_; }

  // Per-phase timing (StepStats::time_*): CUDA events on the GPU, which cost
  // no wait; off by default, and the times read zero.
  void set_phase_timing(bool on) { timing_ = on; }

  // Copies positions, orientations and velocities back into the BodySet.
  void syncHost() { manager_.syncHost(stream_); }

  Bodies<Device, T>& bodies() { return manager_.device(); }
  Contacts<Device, T, Model>& contacts() { return contacts_; }
  BodyManager<Device, T>& manager() { return manager_; }

 private:
  // The host side of a queued step; its figures arrive in pinned memory.
  struct Slot {
    StepStats<T> stats;
    detail::StreamMarks<Device, 5> marks;  // start, detected, solved, moved, figures written
    bool timed = false;
    bool verdict_pending = false;  // the solver's verdict is read with the figures (solve_queued)
  };

  // The slot of this step still holds the step before the previous one, which
  // stays readable (previous_stats) until this step has been queued in full.
  void queue_step() {
    auto& bodies = manager_.device();
    const SolverSettings<T>& s = settings_;
    const math::Vector3<T> g(s.gravity[0], s.gravity[1], s.gravity[2]);
    const std::size_t k = steps_ % 2;
    Slot& slot = slots_[k];
    StepStats<T> stats;
    bool pending = false;
    try {
      if (timing_) slot.marks.mark(0, stream_);
      detection_.set_graphs(s.detection_graph);
      detection_.detect(bodies, contacts_, s.margin, s.friction, stream_);
      if (timing_) slot.marks.mark(1, stream_);
      constexpr bool own_integration = !integrates<solver_type>::value;  // else the solver moves the bodies
      if (own_integration) apply_forces(bodies, s.dt, g, stream_);  // the LCP sees v + dt M^-1 f_ext (thesis Eq. 6)
      const bool warm = s.warm_start > 0;
      if (warm) warm_.carry(contacts_.view(), s.warm_start, stream_);
      if constexpr (queues_verdict<solver_type, Device, T, Model>::value)  // no wait for the verdict
        pending = solver_.solve_queued(bodies, contacts_, s, stream_, warm, k, stats.solver);
      else
        stats.solver = solver_.solve(bodies, contacts_, s, stream_, warm);
      if (timing_) slot.marks.mark(2, stream_);
      if (figures_.size() == 0) figures_ = Figures(2);
      const auto cv = contacts_.view();
      if (own_integration) {  // the move, the warm start's memory and the figures in one pass: "integration"
        const auto bv = bodies.view();
        auto keep = warm_.rememberer(cv, warm);
        const detail::StepEnd<decltype(body_move(bv, s.dt)), decltype(keep)> end{body_move(bv, s.dt), keep, bv.size(),
                                                                               warm_.remembered()};
        step_figures_after(algorithms_, end, bv, cv, g, figures_.data() + k, stream_);
        if (timing_) slot.marks.mark(3, stream_);
      } else {
        if (warm)
          warm_.remember(cv, stream_);
        else
          warm_.forget();
        if (timing_) slot.marks.mark(3, stream_);
        step_figures_into(algorithms_, bodies.view(), cv, g, figures_.data() + k, stream_);
      }
      slot.marks.mark(4, stream_);
    } catch (const NonFiniteStateError& e) {  // found by detection, nothing moved: say which step it stopped
      slot.timed = false;                      // its marks were overwritten
      throw NonFiniteStateError(e.body(), e.field(), steps_);
    } catch (...) {
      slot.timed = false;
      throw;
    }
    slot.stats = stats;
    slot.verdict_pending = pending;
    slot.timed = timing_;
    current_ = k;
    ++steps_;
  }

  StepStats<T> stats_of(std::size_t k) {
    Slot& slot = slots_[k];
    slot.marks.wait(4);
    StepStats<T> st = slot.stats;
    if constexpr (queues_verdict<solver_type, Device, T, Model>::value)
      if (slot.verdict_pending) solver_.verdict(k, st.solver);
    const StepFigures<T> f = figures_.data()[k];
    st.max_penetration = f.max_penetration;
    st.kinetic_energy = f.kinetic_energy;
    st.potential_energy = f.potential_energy;
    if (slot.timed) {
      st.time_detection = slot.marks.seconds(0, 1);
      st.time_solve = slot.marks.seconds(1, 2);
      st.time_integration = slot.marks.seconds(2, 3);
    }
    return st;
  }

  BodyManager<Device, T> manager_;
  stream_t stream_;
  SolverSettings<T> settings_;
  CollisionDetection<Device, T> detection_;
  Contacts<Device, T, Model> contacts_;
  solver_type solver_;
  WarmStart<Device, T, Model> warm_;  // the previous step's impulses (settings.warm_start)
  detail::DeviceAlgorithms<Device> algorithms_;
  // The figures of the last two steps, written by the reduction straight into
  // pinned host memory (mapped into the device's address space).
  using Figures = memory::Buffer<StepFigures<T>, std::conditional_t<std::is_same_v<Device, device::gpu>,
                                                                    memory::CUDAHostAllocator, memory::StandardAllocator>>;
  Figures figures_;
  Slot slots_[2];  // the last two steps queued
  std::size_t steps_ = 0, current_ = 0;
  bool timing_ = false;
};

}  // namespace gpusolve::rbd
