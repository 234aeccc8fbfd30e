// ColouredGaussSeidel: projected Gauss-Seidel made parallel by contact colouring.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/contacts/contact_colouring.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/contact_solver_base.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"
#include "gpusolve/rbd/solvers/program_solve.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// The velocities of a pair's two bodies as its sweep goes: loaded when the
// sweep reaches the pair, moved by each pass's changes (add), and stored once
// after its last pass (store). Each of the pair's points reads its error from
// them (GaussSeidelContact); no other pair of the colour touches a moving body
// of the pair, and a fixed one never changes.
template <class T>
struct PairVelocities : CurrentIterate<T> {
  std::uint32_t a, b;
  bool move_a, move_b;
  math::Vector3<T> va, wa, vb, wb;
  template <class BV>
  GPUSOLVE_HD PairVelocities(const BV& bodies, std::uint32_t a_, std::uint32_t b_)
      : a(a_), b(b_), move_a(bodies.moving(a_)), move_b(bodies.moving(b_)) {
    CurrentIterate<T>::velocity(bodies, a_, va, wa);
    CurrentIterate<T>::velocity(bodies, b_, vb, wb);
  }
  template <class BV>
  GPUSOLVE_HD void velocity(const BV&, std::uint32_t k, math::Vector3<T>& v, math::Vector3<T>& w) const {
    v = k == a ? va : vb;
    w = k == a ? wa : wb;
  }
  template <class Sums>
  GPUSOLVE_HD void add(const Sums& d) {
    if (move_a) va += d.dva, wa += d.dwa;
    if (move_b) vb += d.dvb, wb += d.dwb;
  }
  template <class BV>
  GPUSOLVE_HD void store(const BV& bodies) const {
    for (std::size_t k = 0; k < 3; ++k) {
      if (move_a) bodies.v(a, k) = va[k], bodies.w(a, k) = wa[k];
      if (move_b) bodies.v(b, k) = vb[k], bodies.w(b, k) = wb[k];
    }
  }
};

// The velocity changes of a pass's points, summed in registers (a
// ResolveCollisions sink): stored to memory point by point, each update's loads
// waited for the store before them, a memory round trip or more per point.
template <class T>
struct PassSums {
  math::Vector3<T> dva, dwa, dvb, dwb;
};
template <class T>
struct PassSink {
  PassSums<T>* sums;
  GPUSOLVE_HD void add(std::size_t, const BodyResponse<T>& d) const {
    sums->dva += d.dva, sums->dwa += d.dwa, sums->dvb += d.dvb, sums->dwb += d.dwb;
  }
};

// One body pair's points [first, end) in two passes: in each, every point's
// velocity error from the velocities the pair had when the pass began, and its
// projected update with its 1/k share of a step (InverseBlocks); the pass's
// changes move the pair's velocities at its end, stored after the last pass.
// Gauss-Seidel from pair to pair, Jacobi within one: swept one after another,
// each of a face's points answered the turn its predecessor's impulse gave the
// box, and the fixed order left a sideways push that a finite solve did not
// cancel (the 20-box stack crept 0.56% of a half extent in 10 s and fell at
// 100 to 400 iterations); one pass at 1/k converged too slowly for a tower of
// thin slabs (it sank 1.3% in 10 s), two hold it (docs/methods.md). A pair of
// one point takes one. The first pass records the residual: the change the
// sweep found. Each point's bodies are loaded with its error's data, before
// its impulse (ContactBodies), so that a point costs one memory round trip.
template <class Model, class BV, class CV, class T>
struct GaussSeidelContact {
  CalcNextPhi<Model, BV, CV, T> phi;
  ResolveCollisions<Model, BV, CV, PassSink<T>, T> resolve;  // its sink: each pass's sums
  GPUSOLVE_HD void operator()(std::size_t first, std::size_t end) const {
    const std::size_t passes = end - first > 1 ? 2 : 1;  // one point (every sphere pair): one update
    PairVelocities<T> pair(phi.b, phi.c.a[first], phi.c.b[first]);
    GPUSOLVE_NO_UNROLL
    for (std::size_t p = 0; p < passes; ++p) {
      PassSums<T> sums{};
      ResolveCollisions<Model, BV, CV, PassSink<T>, T> summing = resolve;
      summing.sink.sums = &sums;
      for (std::size_t i = first; i < end; ++i) {
        const ContactBodies<T> bodies(phi.b, phi.c, i);
        T e[Model::rows];
        phi.error(i, e, pair);
        summing.update(i, e, CurrentIterate<T>{}, bodies, p == 0);
      }
      pair.add(sums);
    }
    pair.store(phi.b);
  }
};

// The warm start of a pair (a start program's sweep): the velocity changes of
// its points' impulses in c.x, summed as a pass's (PassSink), stored once.
template <class Model, class BV, class CV, class T>
struct ApplyPairImpulses {
  BV b;
  CV c;
  GPUSOLVE_HD void operator()(std::size_t first, std::size_t end) const {
    PairVelocities<T> pair(b, c.a[first], c.b[first]);
    PassSums<T> sums{};
    const ApplyImpulses<Model, BV, CV, PassSink<T>, T> apply{b, c, {&sums}};
    for (std::size_t i = first; i < end; ++i) apply(i);
    pair.add(sums);
    pair.store(b);
  }
};

// A distributed sweep's velocity changes (BodyExchange): body k's change
// since `before` saved the velocities into row k of `out` (dv, then dw) ...
template <class BV, class T>
struct StoreSweepChanges {
  CopyVelocities<BV, T> before;
  VectorD2View<T> out;  // bodies x 6
  GPUSOLVE_HD void operator()(std::size_t k) const {
    for (std::size_t c = 0; c < 3; ++c)
      out(k, c) = before.b.v(k, c) - before.v(k, c), out(k, 3 + c) = before.b.w(k, c) - before.w(k, c);
  }
};

// ... and, once combined over the ranks, added to the saved velocities.
template <class BV, class T>
struct AddSweepChanges {
  CopyVelocities<BV, T> before;
  VectorD2View<T> in;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    for (std::size_t c = 0; c < 3; ++c)
      before.b.v(k, c) = before.v(k, c) + in(k, c), before.b.w(k, c) = before.w(k, c) + in(k, 3 + c);
  }
};

// A sweep over the colours; in a distributed solve, each rank sweeps its own
// contacts from the velocities the ranks agree on, and every body gets the
// sum of its changes on all ranks that hold it: Gauss-Seidel within a rank,
// Jacobi between ranks, as HCSITS's subdomain sweeps (Preclik and Ruede
// 2015). `before` saves the velocities where the sweep starts.
template <class BV, class T>
struct RankSweep {
  CopyVelocities<BV, T> before;  // restore false: saves
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E, class CV, class F>
  GPUSOLVE_HD void operator()(const E& e, const CV& c, const ColourView& colours, const F& f) const {
    if constexpr (may_exchange<E>::value)
      if (e.exchange != nullptr) return shared(e, c, colours, f);
    sweep_colours(e, c, colours, f);
  }
  template <class E, class CV, class F>
  void shared(const E& e, const CV& c, const ColourView& colours, const F& f) const {
    const std::size_t n = before.b.size();
    e.each(n, before);
    e.sync();
    sweep_colours(e, c, colours, f);
    const VectorD2View<T> sums = e.exchange->sums(n);
    e.each(n, StoreSweepChanges<BV, T>{before, sums});
    e.sync();
    e.combine(n);
    e.each(n, AddSweepChanges<BV, T>{before, sums});
  }
};

// The start program of an attempt (persistent_loop.hpp): the velocities' copy
// for a retry (`saving`), each contact's inverse block, then the velocity
// change of the impulses it starts from, colour by colour (`from_x`: warm
// start). A retry inside the persistent kernel (`retry`) starts cold.
template <class Save, class Blocks, class Apply, class Sweep>
struct GaussSeidelStart {
  Save save;
  Blocks blocks;
  Apply apply;
  ColourView colours;
  Sweep sweep;
  bool saving, from_x;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e, bool retry = false) const {
    if (retry) restart_cold(e, save, blocks.c);
    const bool first = !retry;
    if (saving && first) e.each(save.b.size(), save);  // nothing in this phase writes a velocity
    e.each(blocks.c.size(), blocks);
    e.sync();
    if (from_x && first) sweep(e, blocks.c, colours, apply);
  }
};

// One iteration as a program: a sweep over the colours (`measuring` in the
// last iteration of a run, which records each contact's residual), then in
// the last the residual check's reduction into *residual_out.
template <class Contact, class Sweep, class Residual, class T>
struct GaussSeidelIteration {
  Contact plain, measuring;
  ColourView colours;
  Sweep sweep;
  Residual residual;  // over its width(): max(contacts, bodies)
  T* residual_out;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e, std::size_t, bool last) const {
    sweep(e, plain.phi.c, colours, last ? measuring : plain);
    if (last) reduce_residual(e, residual, residual_out);
  }
};

}  // namespace detail

// Projected (block) Gauss-Seidel over contacts, parallel within a colour: the
// body pairs in contact are coloured on the device every step (ContactColouring)
// so that no two of one colour share a moving body, and one iteration sweeps the
// colours in order, each pair seeing the velocities its predecessors in the
// sweep left (a pair's own points step together: GaussSeidelContact).
// The GPU form of the sequential reference (pgs.hpp), as in PhysX's and Bullet's
// GPU PGS solvers (graph colouring: Tonge, Benevolenski and Voroshilov 2012 use
// it for their mass-splitting Jacobi; Harada 2011, "A parallel constraint solver
// for a rigid body simulation"). It converges in fewer iterations than Jacobi and
// needs no under-relaxation (omega 1 by default). Its colours are phases of one
// persistent kernel with a barrier between them, as PhysX partitions its GPU
// solver (up to SolverSettings::persistent_max_contacts, where the GPU can),
// or one launch per colour (graphs with SolverSettings::graphs); checks and
// retries as in JacobiSolver (ProgramSolve). Deterministic on both backends.
// Same contract as every solver (solver.hpp).
template <class Device, class T, class Model>
class ColouredGaussSeidelSolver : public ContactSolverBase<Device, T, Model> {
  using Base = ContactSolverBase<Device, T, Model>;

 public:
  static constexpr double default_omega = 1.0;
  using typename Base::BodyStore;
  using typename Base::BV;
  using typename Base::ContactStore;
  using typename Base::CV;

  SolverStats<T> solve(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s,
                       stream_t stream = stream_t{}, bool from_x = false) {
    SolverStats<T> stats;
    const BV b = bodies.view();
    const CV c = contacts.view();
    if (!this->prepare(c, s, stats) && run_.exchange() == nullptr) return stats;
    colouring_.build(b, c, stream);
    stats.colours = colouring_.colours();
    const detail::ColourView colours = colouring_.view();
    const std::size_t width = c.size() > b.size() ? c.size() : b.size();
    run_.prepare(this->residual_terms(b, c), width, s, stream);
    const T omega = omega_of<ColouredGaussSeidelSolver>(s);
    if (run_.exchange() != nullptr) sweep_start_.reserve(b);
    const detail::RankSweep<BV, T> sweep{sweep_start_.saver(b)};
    // Each attempt's start: a pair's k points take 1/k of a step each, as in
    // Jacobi (GaussSeidelContact updates them together).
    auto start = [&](bool first_attempt) {
      return detail::GaussSeidelStart<detail::CopyVelocities<BV, T>, InverseBlocks<Model, BV, CV, T>,
                                      detail::ApplyPairImpulses<Model, BV, CV, T>, detail::RankSweep<BV, T>>{
          this->start_.saver(b), {b, c, run_.scale()}, {b, c}, colours, sweep,
          first_attempt && s.max_retries > 0, from_x && first_attempt};
    };
    const VectorD2View<T> rhs{};  // GaussSeidelContact keeps each error in registers: no store
    using Contact = detail::GaussSeidelContact<Model, BV, CV, T>;
    const Contact plain{{b, c, rhs, T(1) / s.dt, s.correction}, {b, c, rhs, {nullptr}, omega, false, this->residual_.view()}};
    Contact measuring = plain;
    measuring.resolve.measure = true;
    const auto terms = this->residual_terms(b, c);
    const detail::GaussSeidelIteration<Contact, detail::RankSweep<BV, T>, decltype(terms), T> iteration{
        plain, measuring, colours, sweep, terms, run_.residual_out()};
    if (!from_x) contacts.x.fill(T(0), stream);
    if (run_.persistent(contacts.expected_size(), s)) {
      if (s.max_retries > 0) this->start_.reserve(b);
      run_.run_persistent(start(true), iteration, detail::NoStart{}, s, omega, width, 0, false, nullptr, stream,
                          stats);
    } else {
      run_.run_launched(b, contacts.x, this->start_, s, omega, start, iteration, [](const auto&) {}, stream, stats);
    }
    return stats;
  }

  const ContactColouring<Device>& colouring() const { return colouring_; }

  // A distributed solve (rbd/distributed/): each rank sweeps its own contacts,
  // the bodies' changes of a sweep and every reduction are shared over the
  // ranks through `exchange` (nullptr: none), as launches (detail::RankSweep).
  // A rank without contacts still takes part in every exchange.
  void set_exchange(BodyExchange<T>* exchange) { run_.set_exchange(exchange); }

 private:
  ContactColouring<Device> colouring_;
  VelocitySnapshot<Device, T> sweep_start_;  // a distributed sweep's start (detail::RankSweep)
  detail::ProgramSolve<Device, T> run_;  // the persistent kernel or launches; checks and retries
};

// The method tag (solver.hpp).
struct ColouredGaussSeidel {
  template <class Device, class T, class Model>
  using solver = ColouredGaussSeidelSolver<Device, T, Model>;
  static constexpr const char* name = "gauss-seidel";
};

}  // namespace gpusolve::rbd
