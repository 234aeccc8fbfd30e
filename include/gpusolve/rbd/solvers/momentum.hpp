// Momentum policies of the Jacobi solver: none (projected Jacobi, thesis 5.2)
// or Nesterov's, which makes it an accelerated projected gradient method (APGD).
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contacts/extent.hpp"
#include "gpusolve/rbd/execution/persistent_loop.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"

namespace gpusolve::rbd {

// Tags of JacobiSolver's Momentum parameter.
struct NoMomentum {};
struct Nesterov {};

namespace detail {

// The program of NoMomentum between an iteration's contact phase and its body
// phase: a barrier, so that every contact's change is in before the sums.
struct NoStep {
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    e.sync();
  }
};

}  // namespace detail

// Momentum<Tag, Device, T>: begin() sizes an attempt's storage. start() is the
// start program (persistent_loop.hpp) of the attempt's first run, queued when
// its start impulses and velocities agree. iterate() is the iterate
// (iterate.hpp) the iterations' contact and body phases go through; program()
// runs between the two phases of an iteration that goes on (it must end in a
// barrier, which it may take from a sum), after_iteration(e) where a run of
// iterations ends without the last one's program; all valid after begin().
template <class Tag, class Device, class T>
class Momentum {
 public:
  template <class BV, class CV>
  void begin(const BV&, const CV&) {}
  template <class BV, class CV>
  detail::NoStart start(const BV&, const CV&) {
    return {};
  }
  detail::CurrentIterate<T> iterate() { return {}; }
  detail::NoStep program() { return {}; }
  template <class E>
  void after_iteration(const E&) {}
};

namespace detail {

// The momentum's scalars: {theta, beta for the contact phase, restart test,
// beta for the body phase}.
enum : std::size_t { theta_slot, beta_slot, uphill_slot, body_beta_slot, momentum_slots };

// Nesterov's sequence theta_{k+1} solving theta_{k+1}^2 = (1 - theta_{k+1})
// theta_k^2, beta = theta_k (1 - theta_k) / (theta_k^2 + theta_{k+1}); a step
// that went uphill (gradient . step > 0) restarts it (O'Donoghue and Candes
// 2015, "Adaptive restart for accelerated gradient schemes"), as Mazhar et al.
// 2015 do in APGD.
template <class T>
struct UpdateMomentum {
  T* state;
  GPUSOLVE_HD void operator()(std::size_t) const {
    const T theta = state[theta_slot];
    if (!(state[uphill_slot] <= T(0))) {  // uphill, or not finite: restart
      state[theta_slot] = T(1), state[beta_slot] = T(0);
      return;
    }
    const T t2 = theta * theta;
    const T next = (-t2 + std::sqrt(t2 * t2 + 4 * t2)) / 2;
    state[beta_slot] = theta * (T(1) - theta) / (t2 + next);
    state[theta_slot] = next;
  }
};

// The iterate of Nesterov's method: an iteration starts from y = x + beta (x -
// x_prev), for the impulses and, since velocities are affine in the impulses,
// for the bodies' velocities (a body that does not move has v = v_prev). x and v hold the last projected iterate;
// y is formed where it is read (each contact's start, each body's velocities in
// the errors and the sums) instead of in a pass of its own, and the new x keeps
// the old one as x_prev. store() also writes the contact's term of the restart
// test, e . (x_{k+1} - x_k), e being the gradient at y. The contact phase reads
// beta from beta_slot while the one thread that updates the momentum may write
// it again after the phase, so the body phase reads its copy, body_beta_slot,
// which contact 0 writes.
template <class T>
struct ExtrapolatedIterate {
  static constexpr bool bodies_first = false;  // iterate.hpp
  VectorD2View<T> px, pv, pw;
  VectorD1View<T> uphill;  // per contact
  T* state;
  template <class CV, std::size_t R>
  GPUSOLVE_HD void start(const CV& c, std::size_t i, T (&x)[R], T (&y)[R]) const {
    const T beta = state[beta_slot];
    for (std::size_t r = 0; r < R; ++r) {
      x[r] = c.x(i, r);
      y[r] = x[r] + beta * (x[r] - px(i, r));
    }
  }
  template <class BV>
  GPUSOLVE_HD void velocity(const BV& b, std::uint32_t k, math::Vector3<T>& v, math::Vector3<T>& w) const {
    const T beta = state[beta_slot];
    for (std::size_t c = 0; c < 3; ++c) {
      const T vc = b.v(k, c), wc = b.w(k, c);
      v[c] = vc + beta * (vc - pv(k, c));
      w[c] = wc + beta * (wc - pw(k, c));
    }
  }
  template <class CV, std::size_t R>
  GPUSOLVE_HD void store(const CV& c, std::size_t i, const T (&e)[R], const T (&x0)[R], const T (&x)[R]) const {
    T s = 0;
    for (std::size_t r = 0; r < R; ++r) {
      s += e[r] * (x[r] - x0[r]);
      px(i, r) = x0[r];
      c.x(i, r) = x[r];
    }
    uphill[i] = s;
    if (i == 0) state[body_beta_slot] = state[beta_slot];
  }
  template <class BV>
  GPUSOLVE_HD void add(const BV& b, std::size_t k, const T (&sv)[3], const T (&sw)[3]) const {
    const T beta = state[body_beta_slot];
    T v[3], w[3], v0[3], w0[3];  // every load before the first store (CurrentIterate::add)
    for (std::size_t c = 0; c < 3; ++c) v[c] = b.v(k, c), w[c] = b.w(k, c), v0[c] = pv(k, c), w0[c] = pw(k, c);
    for (std::size_t c = 0; c < 3; ++c) {
      b.v(k, c) = v[c] + beta * (v[c] - v0[c]) + sv[c];
      b.w(k, c) = w[c] + beta * (w[c] - w0[c]) + sw[c];
      pv(k, c) = v[c], pw(k, c) = w[c];
    }
  }
};

// Reads contact i's term of the restart test.
template <class T>
struct UphillTerm {
  VectorD1View<T> uphill;
  GPUSOLVE_HD T operator()(std::size_t i) const { return uphill[i]; }
};

// Between the contact and the body phase: the restart test's sum (its barrier
// is the one the body phase needs; each index reads back the terms it wrote
// itself), then theta and beta, by the one thread that holds the sum.
template <class T>
struct NesterovStep {
  UphillTerm<T> term;
  Extent contacts;
  UpdateMomentum<T> update;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    e.sum(contacts.size(), term, update.state + uphill_slot);
    e.each(1, update);
  }
};

// The start of an attempt: theta = 1, beta = 0, and the start kept as x_prev.
template <class BV, class CV, class T>
struct ResetMomentum {
  BV b;
  CV c;
  VectorD2View<T> px, pv, pw;
  T* state;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (i == 0)
      for (std::size_t k = 0; k < momentum_slots; ++k) state[k] = k == theta_slot ? T(1) : T(0);
    if (i < c.size())
      for (std::size_t r = 0; r < px.size_y(); ++r) px(i, r) = c.x(i, r);
    if (i < b.size())
      for (std::size_t k = 0; k < 3; ++k) pv(i, k) = b.v(i, k), pw(i, k) = b.w(i, k);
  }
};

// The momentum's start program: ResetMomentum over contacts and bodies.
template <class BV, class CV, class T>
struct StartMomentum {
  ResetMomentum<BV, CV, T> reset;
  std::size_t n;  // max(contacts' bound, bodies)
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    e.each(n, reset);
    e.sync();
  }
};

}  // namespace detail

// Nesterov momentum: the iterate the next Jacobi step starts from is extrapolated
// past the last one (ExtrapolatedIterate). It adds no pass of its own: one sum and
// one single-thread phase per iteration. Its scalars stay in the backend's memory
// (no host wait per iteration).
template <class Device, class T>
class Momentum<Nesterov, Device, T> {
 public:
  template <class BV, class CV>
  void begin(const BV& b, const CV& c) {
    gpusolve::detail::ensure_size(px_, c.bound(), c.x.size_y());
    gpusolve::detail::ensure_size(pv_, b.size(), 3);
    gpusolve::detail::ensure_size(pw_, b.size(), 3);
    gpusolve::detail::ensure_size(uphill_, c.bound());
    if (state_.size_x() == 0) state_.resize(detail::momentum_slots);
    contacts_ = c.count;
  }
  template <class BV, class CV>
  detail::StartMomentum<BV, CV, T> start(const BV& b, const CV& c) {
    return {{b, c, px_.view(), pv_.view(), pw_.view(), state_.data()}, c.bound() > b.size() ? c.bound() : b.size()};
  }
  detail::ExtrapolatedIterate<T> iterate() {
    return {px_.view(), pv_.view(), pw_.view(), uphill_.view(), state_.data()};
  }
  detail::NesterovStep<T> program() { return {{uphill_.view()}, contacts_, {state_.data()}}; }
  template <class E>
  void after_iteration(const E& e) {
    program()(e);
  }

 private:
  VectorD2<T, device_is<Device>> px_, pv_, pw_;
  VectorD1<T, device_is<Device>> uphill_, state_;
  detail::Extent contacts_;
};

}  // namespace gpusolve::rbd
