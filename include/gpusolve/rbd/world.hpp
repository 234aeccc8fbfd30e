// World: one rigid-body simulation on one backend: bodies, contacts, settings,
// and step() = collision detection + contact solve + integration.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/statistics/accuracy.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/bodies/spatial_order.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "gpusolve/rbd/contact_models/contact_model.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/execution/unattended.hpp"
#include "gpusolve/rbd/execution/stream_marks.hpp"
#include "gpusolve/memory/allocation_label.hpp"
#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/memory/cuda_host_allocator.hpp"
#include "gpusolve/memory/standard_allocator.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"
#include "gpusolve/rbd/solvers/accelerated_cg.hpp"
#include "gpusolve/rbd/solvers/coloured_gauss_seidel.hpp"
#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/solvers/substepping.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"
#include "gpusolve/rbd/solvers/warm_start.hpp"

namespace gpusolve::rbd {

namespace detail {
// The end of a step for index i: body i's move and contact i's impulse kept
// for the next step's warm start (fused with the step's figures).
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
// The defaults, APGD with the per-body gather and the isotropic cone, are the
// atlas's best at equal penetration (docs/tuning/solve.md). Shapes: the shape
// kinds the World compiles in (shapes.hpp); a program of spheres and planes
// compiles much faster with spheres_and_planes (SphereWorld, below;
// docs/build_time.md), and a body of another kind is refused by name.
//
// A step is five stages, queued in this order (queue_step):
//   detect       contacts from the bodies' bounds and shapes (collision/)
//   warm start   each persisting contact starts from a share of its last impulse
//                (and keeps its friction anchor, from the velocities the last step ended with)
//   apply forces v + dt M^-1 f_ext, the velocity the contact solve sees (thesis Eq. 6)
//   solve        the Solver concept (solvers/): constrained velocities and impulses
//   end of step  integrate, remember the impulses, write the figures: one pass
template <class Device, class T = float, class Model = ConeFriction, class Method = AcceleratedJacobi<Gather>,
          ShapeMask Shapes = all_shapes>
class World {
 public:
  using solver_type = solver_t<Method, Device, T, Model>;
  static_assert(is_solver<solver_type, Device, T, Model>::value,
                "World: Method::solver must model the Solver concept (gpusolve/rbd/solvers/solver.hpp)");

  World(BodySet<T>& set, const SolverSettings<T>& settings, stream_t stream = stream_t{});

  // Throws InvalidArgumentError naming the field before anything changes.
  void set_settings(const SolverSettings<T>& s);
  const SolverSettings<T>& settings() const { return settings_; }

  // Runs one step and returns its statistics (waits for them).
  StepStats<T> step();

  // Queues `steps` steps. The host waits only where the step's sizes need it
  // (the contact count after detection) and, on the solver's launched path or
  // where a divergence must throw, for the solver's checks; never for timing or
  // statistics. Under the persistent kernel the solver's verdict is read with
  // the step's statistics. Throws NonFiniteStateError naming
  // the body and the step when a body's state holds a NaN or infinity: that
  // step is not taken and no body changes.
  void advance(std::size_t steps = 1);

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
  void advance_unattended(std::size_t steps = 1);

  // Waits for the steps advance_unattended() queued and settles them (see there).
  void finish();

  // Statistics of the last step queued; waits until the backend finished it.
  StepStats<T> latest_stats();
  // Statistics of the step before it: ready without a wait once a later step
  // was queued by advance() (its detection waited for the device). Zero before two steps.
  StepStats<T> previous_stats();
  std::size_t steps_queued() const { return steps_; }
  // Steps advance_unattended() queued again after they were held for a
  // contact list too small, as of the last finish() (each costs a step's
  // time; the list grows each time).
  std::size_t steps_requeued() const { return unattended_.requeued(); }

  // Per-phase timing (StepStats::time_*): CUDA events on the GPU, which cost
  // no wait; off by default, and the times read zero.
  void set_phase_timing(bool on) { timing_ = on; }

  // Copies positions, orientations and velocities back into the BodySet.
  void syncHost();

  // Puts the bodies on the device in spatial order (SpatialOrder: a Morton
  // curve over the moving bodies' centres, the fixed ones after them), so that
  // the contacts' reads of their two bodies stay near each other in memory.
  // The BodySet's indices keep naming the same bodies (manager().slot(i) is
  // body i's place in bodies()); the warm start follows its pairs; contacts()
  // keeps the last step's slots until the next step detects again. Also run
  // every settings().reorder_every steps by advance() and advance_unattended()
  // (which waits for the steps queued before each reorder). Not for a distributed
  // World (its ranks keep their bodies in global-id order): UnsupportedError.
  void reorder_bodies();

  // Runs the solves distributed (rbd/distributed/ sets it): the bodies' sums
  // and every reduction of the solver go through `exchange` (nullptr: none).
  // Throws UnsupportedError naming the method where it does not run
  // distributed (solves_distributed: every method of the library's does; a
  // solver of one's own needs set_exchange).
  void set_exchange(BodyExchange<T>* exchange);
  bool distributed() const { return distributed_; }
  // The contacts the last step remembered for the next one's warm start, on
  // the host, and remember() of such contacts (after the BodySet was
  // rewritten and synced, their pairs renumbered and sorted): rbd/distributed/
  // moves them between ranks with their bodies.
  RememberedContacts<T> remembered_contacts();
  void remember(const RememberedContacts<T>& kept);

  Bodies<Device, T>& bodies();
  Contacts<Device, T, Model>& contacts();
  BodyManager<Device, T>& manager();

 private:
  // The points of a step that its marks record.
  enum Mark : std::size_t { begun, detected, solved, moved, figures_written, marks };

  // The host side of a queued step; its figures arrive in pinned memory.
  struct Slot {
    StepStats<T> stats;
    detail::StreamMarks<Device, marks> marks_;
    bool timed = false;
    bool verdict_pending = false;  // the solver's verdict is read with the figures (solve_queued)
  };

  // Queues the stages of one step. The slot of this step still holds the step
  // before the previous one, which stays readable (previous_stats) until this
  // step has been queued in full. `hold`: UnattendedSteps::hold() for a step
  // queued unattended (its contact count stays on the device and every kernel
  // after detection does nothing while the step is held), else nullptr.
  void queue_step(std::uint32_t* hold) {
    const std::size_t k = steps_ % 2;
    Slot& slot = slots_[k];
    StepStats<T> stats;
    bool pending = false;
    try {
      require_model_materials();
      mark(slot, begun);
      {
        const memory::AllocationLabel label("collision detection");
        detect(hold);
      }
      mark(slot, detected);
      const bool warm = warm_start(hold);  // before the forces: friction anchors read the last step's velocities
      apply_forces(hold);
      {
        const memory::AllocationLabel label("the solver");
        pending = solve(warm, hold, k, stats.solver);
      }
      mark(slot, solved);
      {
        const memory::AllocationLabel label("the warm start and the step's figures");
        end_step(warm, hold, k, slot);
      }
      slot.marks_.mark(figures_written, stream_);
    } catch (const NonFiniteStateError& e) {  // found by detection, nothing moved: say which step it stopped
      slot.timed = false;                      // its marks were overwritten
      throw NonFiniteStateError(manager_.body(e.body()), e.field(), steps_);
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

  // Whether the next step is one before which reorder_every puts the bodies in order.
  bool reorder_due() const {
    return settings_.reorder_every != 0 && steps_ != 0 && steps_ % settings_.reorder_every == 0;
  }

  // A rolling or spinning resistance that the contact model has no rows for
  // is refused by name, not ignored: the materials once per change of the
  // list, the settings in set_settings.
  void require_model_materials() {
    if constexpr (!Contacts<Device, T, Model>::angular) {
      const MaterialList<T>& list = manager_.host().materials();
      if (list.version() == materials_checked_) return;
      refuse_angular_resistance(list, "the World's contact model has no angular rows (use ConeRollingFriction)");
      materials_checked_ = list.version();
    }
  }

  // Friction anchors (ContactSettings::friction_anchors) where the scene holds a
  // kind other than spheres and planes; the warm start keeps them.
  bool anchoring() {
    const bool kinds = (manager_.device().shapes & ~spheres_and_planes) != 0;
    return settings_.friction_anchors && settings_.warm_start > 0 && kinds;
  }

  void detect(std::uint32_t* hold) {
    const SolverSettings<T>& s = settings_;
    contacts_.keep_anchors(anchoring());
    detection_.set_graphs(s.detection_graph);
    detection_.set_contacts_per_body(s.contacts_per_body);
    const ContactDefaults<T> defaults({s.friction, s.restitution, s.rolling, s.spinning}, s.bounce_threshold, s.dt);
    if (hold != nullptr)
      detection_.detect_queued(manager_.device(), contacts_, s.margin, defaults, hold, stream_);
    else
      detection_.detect(manager_.device(), contacts_, s.margin, defaults, stream_);
  }

  void apply_forces(const std::uint32_t* hold) {
    if constexpr (!integrates<solver_type>::value) {  // else the solver moves the bodies
      const auto bv = manager_.device().view();
      if (bv.size() != 0)
        launch(Device{}, bv.size(), detail::UnlessHeld<ApplyForces<BodyView, T>>{{bv, settings_.dt, gravity()}, hold},
               stream_);
    }
  }

  // Returns whether the solve starts from the carried impulses.
  bool warm_start(const std::uint32_t* hold) {
    const bool warm = settings_.warm_start > 0;
    const auto cv = contacts_.view();
    if (warm && cv.bound() != 0) {
      const auto carrier = warm_.carrier(manager_.device().view(), cv, settings_.warm_start, settings_.dt);
      launch(Device{}, cv.bound(), detail::UnlessHeld<decltype(carrier)>{carrier, hold}, stream_);
    }
    return warm;
  }

  // Returns whether the solver's verdict waits in slot k (solve_queued).
  bool solve(bool warm, const std::uint32_t* hold, std::size_t k, SolverStats<T>& stats) {
    auto& bodies = manager_.device();
    if constexpr (solves_unattended<solver_type>::value) solver_.hold_while(hold);
    if constexpr (queues_verdict<solver_type, Device, T, Model>::value) {  // no wait for the verdict
      return solver_.solve_queued(bodies, contacts_, settings_, stream_, warm, k, stats);
    } else {
      stats = solver_.solve(bodies, contacts_, settings_, stream_, warm);
      return false;
    }
  }

  // Integrates, remembers the impulses for the next warm start and writes the
  // figures into slot k: one pass over bodies and contacts where World integrates.
  void end_step(bool warm, std::uint32_t* hold, std::size_t k, Slot& slot) {
    const auto bv = manager_.device().view();
    const auto cv = contacts_.view();
    if constexpr (!integrates<solver_type>::value) {
      auto keep = warm_.rememberer(cv, warm, stream_);
      using End = detail::StepEnd<decltype(body_move(bv, settings_.dt)), decltype(keep)>;
      const detail::CountedUnlessHeld<End> end{{body_move(bv, settings_.dt), keep, bv.size(), warm_.remembered()}, hold};
      step_figures_after(algorithms_, end, bv, cv, gravity(), figures_.data() + k, stream_);
      mark(slot, moved);
    } else {
      if (warm)
        warm_.remember(cv, stream_);
      else
        warm_.forget();
      mark(slot, moved);
      step_figures_into(algorithms_, bv, cv, gravity(), figures_.data() + k, stream_);
    }
  }

  // Steps from `held` on changed nothing: the contacts grow to the count the
  // held detection found and those steps are queued again, or the body that is
  // not finite is named (with the step) and nothing after it is queued.
  void queue_again_from(std::size_t held, const detail::DetectionSummary<T>& summary) {
    const std::size_t queued = steps_;
    steps_ = held;
    current_ = held % 2 == 0 ? 1 : 0;
    try {
      detail::require_usable(summary);
    } catch (const NonFiniteStateError& e) {
      contacts_.resize(summary.contacts < contacts_.capacity() ? summary.contacts : contacts_.capacity());
      throw NonFiniteStateError(manager_.body(e.body()), e.field(), held);
    }
    detection_.grow_for(summary);
    contacts_.resize(summary.contacts);
    unattended_.count_requeued(queued - held);
    advance_unattended(queued - held);
  }

  void mark(Slot& slot, Mark m) {
    if (timing_) slot.marks_.mark(m, stream_);
  }
  math::Vector3<T> gravity() const {
    return math::Vector3<T>(settings_.gravity[0], settings_.gravity[1], settings_.gravity[2]);
  }

  StepStats<T> stats_of(std::size_t k) {
    Slot& slot = slots_[k];
    slot.marks_.wait(figures_written);
    StepStats<T> st = slot.stats;
    if constexpr (queues_verdict<solver_type, Device, T, Model>::value)
      if (slot.verdict_pending) solver_.verdict(k, st.solver);
    const StepFigures<T> f = figures_.data()[k];
    st.solver.contacts = f.contacts;  // the host may not have known it (advance_unattended)
    st.max_penetration = f.max_penetration;
    st.kinetic_energy = f.kinetic_energy;
    st.potential_energy = f.potential_energy;
    if (slot.timed) {
      st.time_detection = slot.marks_.seconds(begun, detected);
      st.time_solve = slot.marks_.seconds(detected, solved);
      st.time_integration = slot.marks_.seconds(solved, moved);
    }
    return st;
  }

  using BodyView = typename Bodies<Device, T>::View;
  // The figures of the last two steps, written by the reduction straight into
  // pinned host memory (mapped into the device's address space).
  using Figures = memory::Buffer<StepFigures<T>, std::conditional_t<std::is_same_v<Device, device::gpu>,
                                                                    memory::CUDAHostAllocator, memory::StandardAllocator>>;

  BodyManager<Device, T> manager_;
  stream_t stream_;
  SolverSettings<T> settings_;
  CollisionDetection<Device, T, Shapes> detection_;
  Contacts<Device, T, Model> contacts_;
  solver_type solver_;
  WarmStart<Device, T, Model> warm_;  // the previous step's impulses (settings.warm_start)
  detail::DeviceAlgorithms<Device> algorithms_;
  Figures figures_{2};
  Slot slots_[2];  // the last two steps queued
  std::size_t steps_ = 0, current_ = 0;
  bool timing_ = false;
  std::size_t materials_checked_ = ~std::size_t(0);  // the MaterialList version require_model_materials passed
  SpatialOrder<Device, T> order_;  // reorder_bodies
  bool distributed_ = false;       // set_exchange
  UnattendedSteps<Device> unattended_;
};

// The members a program calls, defined outside the class: an explicit
// instantiation declaration (prebuilt_worlds.hpp) then leaves them, and the
// kernels they launch, to the prebuilt library (docs/build_time.md).
template <class Device, class T, class Model, class Method, ShapeMask Shapes>
World<Device, T, Model, Method, Shapes>::World(BodySet<T>& set, const SolverSettings<T>& settings, stream_t stream)
    : manager_(set, default_rebuild_threshold, Shapes), stream_(stream) {
  set_settings(settings);
  manager_.syncDeviceFull(stream_);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::set_settings(const SolverSettings<T>& s) {
  s.validate();
  if constexpr (!Contacts<Device, T, Model>::angular)
    if (s.rolling != T(0) || s.spinning != T(0))
      detail::bad_setting(s.rolling != T(0) ? "rolling" : "spinning",
                          "needs a contact model with angular rows (ConeRollingFriction); this World's has none");
  finish();
  if (distributed_ && s.reorder_every != 0)
    detail::bad_setting("reorder_every", "must be 0 in a distributed World (its ranks keep global-id order)");
  settings_ = s;
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
StepStats<T> World<Device, T, Model, Method, Shapes>::step() {
  advance(1);
  return latest_stats();
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::advance(std::size_t steps) {
  finish();
  for (std::size_t k = 0; k < steps; ++k) {
    if (reorder_due()) reorder_bodies();
    queue_step(nullptr);
  }
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::advance_unattended(std::size_t steps) {
  if constexpr (!solves_unattended<solver_type>::value || integrates<solver_type>::value) {
    advance(steps);
  } else {
    if (settings_.throw_on_divergence) return advance(steps);  // the host waits for each verdict
    if (steps_ == 0 && steps > 0) {  // the host counts the first step's contacts: it sizes the solver's grid
      queue_step(nullptr);
      --steps;
    }
    const std::size_t every = settings_.reorder_every;
    while (steps > 0) {
      if (reorder_due()) reorder_bodies();  // waits for the steps queued before it
      const std::size_t to_reorder = every != 0 ? every - steps_ % every : steps;
      const std::size_t run = steps < to_reorder ? steps : to_reorder;
      unattended_.begin(steps_, stream_);
      for (std::size_t k = 0; k < run; ++k) queue_step(unattended_.hold());
      steps -= run;
    }
  }
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::finish() {
  while (unattended_.pending()) {
    const std::optional<std::size_t> held = unattended_.settle(stream_);
    const auto summary = detection_.summary(stream_);
    contacts_.count_on_device(nullptr);
    if (!held) {
      contacts_.resize(summary.contacts);
      return;
    }
    queue_again_from(*held, summary);
  }
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
StepStats<T> World<Device, T, Model, Method, Shapes>::latest_stats() {
  finish();
  return steps_ == 0 ? StepStats<T>{} : stats_of(current_);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
StepStats<T> World<Device, T, Model, Method, Shapes>::previous_stats() {
  finish();
  return steps_ < 2 ? StepStats<T>{} : stats_of(1 - current_);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::syncHost() {
  finish();
  manager_.syncHost(stream_);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::reorder_bodies() {
  finish();
  if (distributed_)
    throw UnsupportedError("gpusolve: World::reorder_bodies: a distributed World keeps its bodies in global-id order");
  Bodies<Device, T>& bodies = manager_.device();
  const std::size_t n = bodies.size();
  const std::uint32_t* order = order_.compute(bodies, stream_);
  SpatialOrder<Device, T>::apply(bodies, order, stream_);
  warm_.renumber(bodies.view(), order_.inverse(n, stream_), stream_);
  std::vector<std::uint32_t> host(n);
  detail::copy_with_host<Device>(host.data(), order, n, true, stream_);
  manager_.reordered(host);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::set_exchange(BodyExchange<T>* exchange) {
  finish();
  if (exchange != nullptr && settings_.reorder_every != 0)
    detail::bad_setting("reorder_every", "must be 0 in a distributed World (its ranks keep global-id order)");
  if constexpr (solves_distributed<solver_type, T>::value) {
    solver_.set_exchange(exchange);
    distributed_ = exchange != nullptr;
  } else if (exchange != nullptr)
    throw UnsupportedError(std::string("gpusolve: World::set_exchange: the method '") + Method::name +
                           "' does not run distributed (its solver has no set_exchange; every method of the "
                           "library's has)");
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
RememberedContacts<T> World<Device, T, Model, Method, Shapes>::remembered_contacts() {
  finish();
  return warm_.host_copy(stream_);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
void World<Device, T, Model, Method, Shapes>::remember(const RememberedContacts<T>& kept) {
  finish();
  warm_.restore(kept);
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
Bodies<Device, T>& World<Device, T, Model, Method, Shapes>::bodies() {
  finish();
  return manager_.device();
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
Contacts<Device, T, Model>& World<Device, T, Model, Method, Shapes>::contacts() {
  finish();
  return contacts_;
}

template <class Device, class T, class Model, class Method, ShapeMask Shapes>
BodyManager<Device, T>& World<Device, T, Model, Method, Shapes>::manager() {
  finish();
  return manager_;
}

// A World of spheres and planes only: the sphere path of detection alone is
// compiled in.
template <class Device, class T = float, class Model = ConeFriction, class Method = AcceleratedJacobi<Gather>>
using SphereWorld = World<Device, T, Model, Method, spheres_and_planes>;

}  // namespace gpusolve::rbd
