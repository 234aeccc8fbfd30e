// JacobiSolver: the projected, under-relaxed block Jacobi LCP solver of thesis
// 5.2 (Algorithm 1), run on the backend where bodies and contacts live.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/solvers/accumulation.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/contact_solver_base.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/momentum.hpp"
#include "gpusolve/rbd/solvers/program_solve.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/rbd/execution/persistent_loop.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// One iteration of the Jacobi family as an iteration program
// (persistent_loop.hpp): every contact's projected update (`measuring` in the
// last iteration of a run, which records the residual), then, unless it is the
// last, the momentum's step (Step, which ends in the barrier the next phase
// needs), then their sum per body (Apply, the accumulation strategy). Contact
// and body phases go through the momentum's iterate (iterate.hpp), so a
// momentum method costs no phase of its own: two barriers per iteration
// (Atomic without momentum needs one: RotatedJacobiIteration). The
// last iteration of a run ends in the residual check's reduction (Residual,
// convergence.hpp) into *residual_out, inside a persistent kernel as well.
template <class Contact, class Apply, class Step, class Residual, class T>
struct JacobiIteration {
  Contact plain, measuring;
  Apply apply;
  Step momentum;
  Residual residual;  // over its width(): max(contacts, bodies)
  T* residual_out;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e, std::size_t, bool last) const {
    if (last) {
      e.each(plain.phi.c.size(), measuring);
      e.sync();
    } else {
      e.each(plain.phi.c.size(), plain);
      momentum(e);
    }
    apply(e);
    e.sync();
    if (last) reduce_residual(e, residual, residual_out);
  }
};

// Contact i and body i of a rotated phase (AtomicRotation): the body's loads
// are issued first, so that they overlap the contact's, and its stores last.
// An index past the bodies loads the last body (there is one wherever there
// is a contact) and stores nothing: no branch around the loads.
template <class Contact, class T>
struct ContactAndBody {
  Contact contact;
  RotateBody<T> body;
  std::size_t contacts, bodies;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    T x[12];
    body.load(i < bodies ? i : bodies - 1, x);
    if (i < contacts) contact(i);
    if (i < bodies) body.store(i, x);
  }
};

// JacobiIteration in one phase, for Atomic without momentum (AtomicRotation,
// accumulation.hpp): iteration k's contacts and its body updates share one
// phase and one barrier. The last iteration of a run adds the fold of the
// rotation into the bodies' velocities before the residual's reduction.
template <class Contact, class Residual, class T>
struct RotatedJacobiIteration {
  Contact plain, measuring;  // their sink and iterate are iteration k's
  AtomicRotation<T> rotation;
  std::size_t bodies;
  Residual residual;
  T* residual_out;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e, std::size_t k, bool last) const {
    if (last)
      phase(e, k, measuring);
    else
      phase(e, k, plain);
    if (last) {
      e.each(bodies, rotation.fold(k));
      e.sync();
      reduce_residual(e, residual, residual_out);
    }
  }
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void phase(const E& e, std::size_t k, Contact contact) const {
    contact.resolve.sink = rotation.sink(k);
    contact.iterate = rotation.iterate(k);
    const std::size_t contacts = contact.phi.c.size();
    e.each(contacts > bodies ? contacts : bodies,
           ContactAndBody<Contact, T>{contact, rotation.body(k), contacts, bodies});
    e.sync();
  }
};

// The start program of an attempt: each contact's inverse block and the
// velocity change of the impulses it starts from (`from_x`: warm start,
// ApplyImpulses and their sums per body), then the momentum's start
// (Momentum::start). In a solve's first attempt, first the accumulator's
// preparation when the solver did not launch it (`preparing`), and the
// velocities' copy for a retry (`saving`). With `retry` (inside the persistent
// kernel, which retries on its own), first what solve_relaxed does on the host
// between attempts: the velocities the solve began with back, zero impulses;
// then a cold start. One program for both, so that the kernel holds its code
// once. Under a persistent kernel it costs barriers instead of launches.
template <class Prepare, class Save, class Blocks, class Warm, class Apply, class MomentumStart>
struct AttemptStart {
  Prepare prepare;
  Save save;
  Blocks blocks;
  Warm warm;
  Apply apply;
  MomentumStart momentum;
  bool preparing, saving, from_x;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e, bool retry = false) const {
    if (retry) restart_cold(e, save, warm.c);
    const bool first = !retry;
    if (preparing && first) prepare(e);                // ends with e.sync()
    if (saving && first) e.each(save.b.size(), save);  // nothing in this phase writes a velocity
    e.each(warm.c.size(), blocks);
    if (from_x && first) e.each(warm.c.size(), warm);
    e.sync();
    if (from_x && first) {
      apply(e);
      e.sync();
    }
    momentum(e);
  }
};

// The momentum's step after a check that does not stop, with the barrier that
// a launch boundary gives it on the host: the next run's contacts read its beta.
template <class Step>
struct BetweenRuns {
  Step step;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    step(e);
    e.sync();
  }
};

}  // namespace detail

// Solves the contact LCP of one time step for the bodies' velocities. On entry
// the velocities include the step's external forces (v + dt M^-1 f); on exit
// they are the constrained velocities and contacts.x holds each contact's
// impulse (normal, t, o). The iteration starts from zero impulses, or with
// `from_x` from the admissible impulses in contacts.x (warm start, warm_start.hpp):
// their velocity change J^T x is applied first, so velocities and impulses agree.
// A diverging solve is retried at a smaller omega (relaxation.hpp,
// SolverSettings::max_retries); a retry starts from zero impulses and the
// velocities the solve began with (before J^T x), i.e. as a cold solve: the
// starting guess may be what made the first attempt diverge, and the cold start
// needs no copy of it. Under the persistent kernel the residual checks
// (ConvergenceRule) and the retries run on the device, and the host reads the
// verdict once per solve, or later (solve_queued). Scratch storage is kept
// between calls. Strategy:
// UpdateCache, Atomic or Gather (accumulation.hpp). MomentumTag: NoMomentum
// (projected Jacobi) or Nesterov (APGD, momentum.hpp).
template <class Device, class T, class Model, class Strategy = Gather, class MomentumTag = NoMomentum>
class JacobiSolver : public ContactSolverBase<Device, T, Model> {
  using Base = ContactSolverBase<Device, T, Model>;

 public:
  // Undamped Jacobi diverges on piles (thesis 5.2). With momentum the step must
  // stay below 1 / (the largest eigenvalue of Dinv N), which a close-packed pile
  // pushes towards 3 (docs/tuning/solve.md).
  static constexpr double default_omega = std::is_same_v<MomentumTag, Nesterov> ? 0.3 : 0.5;
  using typename Base::BodyStore;
  using typename Base::BV;
  using typename Base::ContactStore;
  using typename Base::CV;

  SolverStats<T> solve(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s,
                       stream_t stream = stream_t{}, bool from_x = false) {
    SolverStats<T> stats;
    queue(bodies, contacts, s, stream, from_x, 0, false, stats);
    return stats;
  }

  // solve() without a wait where the solve runs as one kernel (the persistent
  // kernel: checks and retries on the device) and a divergence need not throw:
  // then it returns true and `stats` holds only what the host knows (contacts,
  // reduction passes) until verdict(slot, stats), called once the stream has
  // passed the solve, fills in the rest. Two slots (0, 1) keep the verdicts of
  // two queued solves apart. Otherwise it is solve(), and returns false.
  bool solve_queued(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s, stream_t stream,
                    bool from_x, std::size_t slot, SolverStats<T>& stats) {
    stats = SolverStats<T>{};
    return queue(bodies, contacts, s, stream, from_x, slot, !s.throw_on_divergence, stats);
  }

  // Fills in the verdict of the solve queued in `slot`: status, iterations,
  // residual history, retries, omega. The stream must have passed it.
  void verdict(std::size_t slot, SolverStats<T>& stats) const { run_.verdict(slot, stats); }

  // Solves whose contacts' count is on the device (Contacts::count_on_device)
  // do nothing while *hold is not 0, a word of the backend's memory that an
  // earlier kernel of the stream may set (World::advance_unattended: a step
  // that must not be taken). nullptr: never held.
  void hold_while(const std::uint32_t* hold) { hold_ = hold; }

  // A distributed solve (rbd/distributed/): the bodies' sums and every
  // reduction of an iteration are shared over the ranks through `exchange`
  // (nullptr: none), as launches. Each rank's contacts are its own; a rank
  // without contacts still takes part in every exchange. Atomic without
  // momentum then runs its iterations unrotated: each iteration's sums are
  // combined before any velocity moves.
  void set_exchange(BodyExchange<T>* exchange) {
    run_.set_exchange(exchange);
  }

 private:
  using Sink = decltype(std::declval<Accumulator<Strategy, Device, T>&>().sink());
  // Atomic without momentum runs an iteration as one phase (RotatedJacobiIteration),
  // unless distributed.
  static constexpr bool rotated = std::is_same_v<Strategy, Atomic> && std::is_same_v<MomentumTag, NoMomentum>;

  // Queues the solve (solve(), solve_queued()) in its stages: prepare, then
  // per attempt its start, runs of iterations and their residual checks, and
  // the verdict. Returns true when it left its verdict in `slot` for verdict()
  // without waiting (`deferred` and the persistent kernel); else `stats` is complete.
  bool queue(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s, stream_t stream, bool from_x,
             std::size_t slot, bool deferred, SolverStats<T>& stats) {
    const BV b = bodies.view();
    CV c = contacts.view();
    const bool persistent = run_.persistent(contacts.expected_size(), s);
    if (!count_on_host(c, persistent, stream)) return false;  // held
    if (!this->prepare(c, s, stats) && run_.exchange() == nullptr) return false;
    const std::size_t width = grid_width(contacts, b, c);
    // The accumulator's preparation (Gather: the grouping's build) runs as the
    // persistent kernel's first phases, or is launched here.
    const auto prepared = acc_.prepare_program(b, c, stream);
    if (!persistent) prepared(launched(stream));
    stats.reduction_passes = acc_.passes();
    prepare_iterations(b, c, s, width, stream);
    if (!from_x) contacts.x.fill(T(0), stream);
    if constexpr (rotated)
      if (run_.exchange() != nullptr) {  // distributed, so launched
        solve_launched(b, c, contacts, s, prepared, iteration_program<false>(b, c, s), from_x, stream, stats);
        return false;
      }
    const auto iteration = iteration_program(b, c, s);
    if (persistent) return solve_persistent(b, c, s, prepared, iteration, from_x, width, slot, deferred, stream, stats);
    solve_launched(b, c, contacts, s, prepared, iteration, from_x, stream, stats);
    return false;
  }

  // Where the contacts' count is on the device, a launched solve (and the
  // update cache, whose passes are counted on the host) reads it, and the hold,
  // on the host. Returns false for a held step.
  bool count_on_host(CV& c, bool persistent, stream_t stream) const {
    if (c.count.live == nullptr || (persistent && !std::is_same_v<Strategy, UpdateCache>)) return true;
    if (hold_ != nullptr && detail::read_back<Device>(hold_, 0, stream) != 0) return false;
    const std::size_t live = detail::read_back<Device>(c.count.live, 0, stream);
    c.count = {live < c.bound() ? live : c.bound(), nullptr};
    return true;
  }

  // The persistent grid's width: the contacts the host expects, a sixteenth
  // more (its phases stride over whatever count the device holds, but a grid
  // short of it gives threads a second contact; docs/tuning/execution.md), or the bodies.
  static std::size_t grid_width(const ContactStore& contacts, const BV& b, const CV& c) {
    const std::size_t expected = contacts.expected_size() + contacts.expected_size() / 16;
    const std::size_t nc = c.count.live != nullptr ? (expected < c.bound() ? expected : c.bound()) : c.bound();
    return nc > b.size() ? nc : b.size();
  }

  // What every run of iterations needs before it starts: the momentum's
  // state, the residual's slot, the reductions' storage, the blocks' scale.
  void prepare_iterations(const BV& b, const CV& c, const SolverSettings<T>& s, std::size_t width, stream_t stream) {
    momentum_.begin(b, c);
    run_.prepare(this->residual_terms(b, c), width, s, stream);
  }

  detail::LaunchExec<Device, T> launched(stream_t stream) { return run_.launched(stream); }

  // The start of the first attempt (in the kernel, the accumulator's
  // preparation first; the copy of the velocities for a retry; the warm start)
  // or of a retry (cold).
  template <class Prepared>
  auto attempt_start(const BV& b, const CV& c, const SolverSettings<T>& s, const Prepared& prepared, bool persistent,
                     bool first_attempt, bool from_x) {
    return detail::AttemptStart<Prepared, detail::CopyVelocities<BV, T>, InverseBlocks<Model, BV, CV, T>,
                                ApplyImpulses<Model, BV, CV, Sink, T>, decltype(acc_.program(b)),
                                decltype(momentum_.start(b, c))>{prepared,
                                                                 this->start_.saver(b),
                                                                 {b, c, run_.scale()},
                                                                 {b, c, acc_.sink()},
                                                                 acc_.program(b),
                                                                 momentum_.start(b, c),
                                                                 persistent && first_attempt,
                                                                 first_attempt && s.max_retries > 0,
                                                                 from_x && first_attempt};
  }

  // One iteration as a program (JacobiIteration, or RotatedJacobiIteration
  // where Rotated): every attempt iterates at the first attempt's omega; a
  // retry's smaller omega scales the inverse blocks instead
  // (InverseBlocks::scale), so that the persistent kernel retries with the
  // iteration it holds.
  template <bool Rotated = rotated>
  auto iteration_program(const BV& b, const CV& c, const SolverSettings<T>& s) {
    const T omega = omega_of<JacobiSolver>(s);
    const VectorD2View<T> rhs{};  // JacobiContact keeps each error in registers: no store
    const auto residual = this->residual_.view();
    const auto terms = this->residual_terms(b, c);
    T* const residual_out = run_.residual_out();
    // The iteration's contact functors, plain and measuring, for a sink and an iterate.
    auto contact_pair = [&](const auto& sink, const auto& look) {
      using Contact = JacobiContact<Model, BV, CV, std::decay_t<decltype(sink)>, T, std::decay_t<decltype(look)>>;
      const Contact plain{{b, c, rhs, T(1) / s.dt, s.correction}, {b, c, rhs, sink, omega, false, residual}, look};
      Contact measuring = plain;
      measuring.resolve.measure = true;
      return std::pair<Contact, Contact>{plain, measuring};
    };
    if constexpr (Rotated) {
      const auto r = acc_.rotation(b);
      const auto [plain, measuring] = contact_pair(r.sink(1), r.iterate(1));
      return detail::RotatedJacobiIteration<std::decay_t<decltype(plain)>, decltype(terms), T>{
          plain, measuring, r, b.size(), terms, residual_out};
    } else {
      const auto look = momentum_.iterate();
      const auto [plain, measuring] = contact_pair(acc_.sink(), look);
      return detail::JacobiIteration<std::decay_t<decltype(plain)>, decltype(acc_.program(b, look)),
                                     decltype(momentum_.program()), decltype(terms), T>{
          plain, measuring, acc_.program(b, look), momentum_.program(), terms, residual_out};
    }
  }

  // The whole solve as one kernel: checks and retries run in it, and the host
  // waits for its verdict at most (not at all when `deferred`).
  template <class Prepared, class Iteration>
  bool solve_persistent(const BV& b, const CV& c, const SolverSettings<T>& s, const Prepared& prepared,
                        const Iteration& iteration, bool from_x, std::size_t width, std::size_t slot, bool deferred,
                        stream_t stream, SolverStats<T>& stats) {
    if (s.max_retries > 0) this->start_.reserve(b);
    const auto between = [&] {
      if constexpr (std::is_same_v<MomentumTag, NoMomentum>)
        return detail::NoStart{};
      else
        return detail::BetweenRuns<decltype(momentum_.program())>{momentum_.program()};
    }();
    return run_.run_persistent(attempt_start(b, c, s, prepared, true, true, from_x), iteration, between, s,
                               omega_of<JacobiSolver>(s), width, slot, deferred,
                               c.count.live != nullptr ? hold_ : nullptr, stream, stats);
  }

  // The solve as launches: each attempt's start, then runs of iterations up to
  // each residual check (replayed as a graph with `graphs`), the check read on
  // the host; retries through solve_relaxed.
  template <class Prepared, class Iteration>
  void solve_launched(const BV& b, const CV& c, ContactStore& contacts, const SolverSettings<T>& s,
                      const Prepared& prepared, const Iteration& iteration, bool from_x, stream_t stream,
                      SolverStats<T>& stats) {
    run_.run_launched(
        b, contacts.x, this->start_, s, omega_of<JacobiSolver>(s),
        [&](bool first_attempt) { return attempt_start(b, c, s, prepared, false, first_attempt, from_x); }, iteration,
        [&](const auto& e) { momentum_.after_iteration(e); }, stream, stats);
  }

  Accumulator<Strategy, Device, T> acc_;
  Momentum<MomentumTag, Device, T> momentum_;
  detail::ProgramSolve<Device, T> run_;  // the persistent kernel or launches; checks and retries
  const std::uint32_t* hold_ = nullptr;  // hold_while
};

// The method tag of projected Jacobi (a model of the Solver concept, solver.hpp).
template <class Strategy = Gather>
struct Jacobi {
  template <class Device, class T, class Model>
  using solver = JacobiSolver<Device, T, Model, Strategy>;
  static constexpr const char* name = "jacobi";
};

// The method tag of the accelerated projected gradient method (APGD, Mazhar,
// Heyn, Negrut and Tasora 2015, "Using Nesterov's method to accelerate
// multibody dynamics with friction and contact", ACM TOG 34(3); Chrono's
// ChSolverAPGD): Nesterov's momentum with adaptive restart over the projected
// gradient step, here preconditioned by each contact's inverse block, which
// makes that step one projected Jacobi iteration. Same kernels as Jacobi, plus
// one reduction and two small kernels per iteration; the momentum's scalars
// stay on the device.
template <class Strategy = Gather>
struct AcceleratedJacobi {
  template <class Device, class T, class Model>
  using solver = JacobiSolver<Device, T, Model, Strategy, Nesterov>;
  static constexpr const char* name = "apgd";
};

}  // namespace gpusolve::rbd
