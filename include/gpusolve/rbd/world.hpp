// World: one rigid-body simulation on one backend: bodies, contacts, settings,
// and step() = collision detection + contact solve + integration.
#pragma once

#include <cstddef>
#include <cstdint>
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
#include "gpusolve/rbd/detail/hold.hpp"
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
// A step queued without a wait (`guard` set) does nothing while it is held,
// and counts itself taken at index 0 otherwise.
template <class Move, class Remember>
struct StepEnd {
  Move move;
  Remember remember;
  std::size_t bodies, remembered;  // WarmStart::remembered()
  std::uint32_t* guard;            // World's {hold, steps taken}, or nullptr
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (guard != nullptr) {
      if (guard[0] != 0) return;
      if (i == 0) ++guard[1];
    }
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
    finish();
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
    finish();
    for (std::size_t k = 0; k < steps; ++k) queue_step(false);
  }

  // Queues `steps` steps with no host wait at all, where the method allows it
  // (solves_unattended: the Jacobi family, whose update cache still reads its
  // pass count, and whose launched path above persistent_max_contacts reads
  // its checks) and settings().throw_on_divergence is off; else it is
  // advance(). Each step's contact count stays on the device, its launches
  // sized by the contacts' capacity and the solver's grid by the count the
  // host last knew (a World's first step is taken as advance() takes it). A step
  // that cannot be taken (more contacts than the capacity, a body that is not
  // finite) is held on the device: it and every step after it in the stream
  // change nothing. finish(), which every other member that reads or changes
  // the world calls first, waits for the steps and settles them: it grows the
  // contacts and queues the held steps again, or throws NonFiniteStateError
  // naming the body and the step (the bodies as they were before that step;
  // the steps after it are not taken).
  void advance_unattended(std::size_t steps = 1) {
    if constexpr (!solves_unattended<solver_type>::value || integrates<solver_type>::value) {
      advance(steps);
    } else {
      if (settings_.throw_on_divergence) return advance(steps);  // the host waits for each verdict
      if (guard_.size_x() == 0) {
        guard_.resize(2);
        guard_.fill(0u, stream_);
      }
      if (steps_ == 0 && steps > 0) {  // the host counts the first step's contacts: it sizes the solver's grid
        queue_step(false);
        --steps;
      }
      if (!unsettled_) unsettled_from_ = steps_;
      unsettled_ = true;
      for (std::size_t k = 0; k < steps; ++k) queue_step(true);
    }
  }

  // Waits for the steps advance_unattended() queued and settles them (see there).
  void finish() {
    while (unsettled_) {
      unsettled_ = false;
      const std::uint32_t hold = detail::read_back<Device>(guard_.data(), 0, stream_);
      const std::uint32_t taken_total = detail::read_back<Device>(guard_.data(), 1, stream_);
      const std::size_t taken = std::uint32_t(taken_total - taken_seen_);  // modulo 2^32, as the counter
      taken_seen_ = taken_total;
      const auto s = detection_.summary(stream_);
      contacts_.count_on_device(nullptr);
      if (hold == 0) {
        contacts_.resize(s.contacts);
        return;
      }
      const std::size_t held = unsettled_from_ + taken, queued = steps_;
      steps_ = held;  // the steps from `held` on changed nothing
      current_ = held % 2 == 0 ? 1 : 0;
      guard_.fill(0u, stream_);
      taken_seen_ = 0;
      try {
        detail::require_usable(s);
      } catch (const NonFiniteStateError& e) {
        contacts_.resize(s.contacts < contacts_.capacity() ? s.contacts : contacts_.capacity());
        throw NonFiniteStateError(e.body(), e.field(), held);
      }
      contacts_.resize(s.contacts);  // grows the storage; the held steps are queued again
      requeued_ += queued - held;
      advance_unattended(queued - held);
    }
  }

  // Statistics of the last step queued; waits until the backend finished it.
  StepStats<T> latest_stats() {
    finish();
    return steps_ == 0 ? StepStats<T>{} : stats_of(current_);
  }
  // Statistics of the step before it: ready without a wait once a later step
  // was queued by advance() (its detection waited for the device). Zero before two steps.
  StepStats<T> previous_stats() {
    finish();
    return steps_ < 2 ? StepStats<T>{} : stats_of(1 - current_);
  }
  std::size_t steps_queued() const { return steps_; }
  // Steps advance_unattended() queued again after they were held for a
  // contact list too small, as of the last finish() (each costs a step's
  // time; the list grows each time).
  std::size_t steps_requeued() const { return requeued_; }

  // Per-phase timing (StepStats::time_*): CUDA events on the GPU, which cost
  // no wait; off by default, and the times read zero.
  void set_phase_timing(bool on) { timing_ = on; }

  // Copies positions, orientations and velocities back into the BodySet.
  void syncHost() {
    finish();
    manager_.syncHost(stream_);
  }

  Bodies<Device, T>& bodies() {
    finish();
    return manager_.device();
  }
  Contacts<Device, T, Model>& contacts() {
    finish();
    return contacts_;
  }
  BodyManager<Device, T>& manager() {
    finish();
    return manager_;
  }

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
  // `unattended`: the detection's count stays on the device, and every kernel
  // after it does nothing while the step is held (advance_unattended).
  void queue_step(bool unattended) {
    auto& bodies = manager_.device();
    const SolverSettings<T>& s = settings_;
    const math::Vector3<T> g(s.gravity[0], s.gravity[1], s.gravity[2]);
    const std::size_t k = steps_ % 2;
    Slot& slot = slots_[k];
    StepStats<T> stats;
    bool pending = false;
    std::uint32_t* const guard = unattended ? guard_.data() : nullptr;  // guard[0]: the hold
    try {
      if (timing_) slot.marks.mark(0, stream_);
      detection_.set_graphs(s.detection_graph);
      if (unattended)
        detection_.detect_queued(bodies, contacts_, s.margin, s.friction, guard, stream_);
      else
        detection_.detect(bodies, contacts_, s.margin, s.friction, stream_);
      if constexpr (solves_unattended<solver_type>::value) solver_.hold_while(guard);
      if (timing_) slot.marks.mark(1, stream_);
      constexpr bool own_integration = !integrates<solver_type>::value;  // else the solver moves the bodies
      const Device dev{};
      const auto bv = bodies.view();
      if (own_integration && bv.size() != 0)  // the LCP sees v + dt M^-1 f_ext (thesis Eq. 6)
        launch(dev, bv.size(),
               detail::UnlessHeld<ApplyForces<typename Bodies<Device, T>::View, T>>{{bv, s.dt, g}, guard}, stream_);
      const bool warm = s.warm_start > 0;
      if (warm && contacts_.view().bound() != 0)
        launch(dev, contacts_.view().bound(),
               detail::UnlessHeld<decltype(warm_.carrier(contacts_.view(), s.warm_start))>{
                   warm_.carrier(contacts_.view(), s.warm_start), guard},
               stream_);
      if constexpr (queues_verdict<solver_type, Device, T, Model>::value)  // no wait for the verdict
        pending = solver_.solve_queued(bodies, contacts_, s, stream_, warm, k, stats.solver);
      else
        stats.solver = solver_.solve(bodies, contacts_, s, stream_, warm);
      if (timing_) slot.marks.mark(2, stream_);
      if (figures_.size() == 0) figures_ = Figures(2);
      const auto cv = contacts_.view();
      if (own_integration) {  // the move, the warm start's memory and the figures in one pass: "integration"
        auto keep = warm_.rememberer(cv, warm);
        const detail::StepEnd<decltype(body_move(bv, s.dt)), decltype(keep)> end{body_move(bv, s.dt), keep, bv.size(),
                                                                               warm_.remembered(), guard};
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
    st.solver.contacts = f.contacts;  // the host may not have known it (advance_unattended)
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
  // advance_unattended: {hold, steps taken} in the backend's memory, the
  // steps taken when finish() last read them, and the first step not settled.
  VectorD1<std::uint32_t, device_is<Device>> guard_;
  std::uint32_t taken_seen_ = 0;
  std::size_t unsettled_from_ = 0, requeued_ = 0;
  bool unsettled_ = false;
};

}  // namespace gpusolve::rbd
