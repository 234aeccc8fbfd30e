// Momentum policies of the Jacobi solver: none (projected Jacobi, thesis 5.2)
// or Nesterov's, which makes it an accelerated projected gradient method (APGD).
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/detail/launch_exec.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"
#include "gpusolve/rbd/detail/scratch.hpp"

namespace gpusolve::rbd {

// Tags of JacobiSolver's Momentum parameter.
struct NoMomentum {};
struct Nesterov {};

namespace detail {

// The after_iteration() program of NoMomentum: closes the phase it joins.
struct NoStep {
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    e.sync();
  }
};

}  // namespace detail

// Momentum<Tag, Device, T>: begin() when an attempt's start impulses and
// velocities agree (sizes all its storage); after_iteration() once per iteration that goes on, with
// contacts.x and the velocities at the projected iterate and rhs the gradient
// it was computed from. program(b, c, rhs) is after_iteration() as phases of an
// iteration program (detail/persistent_loop.hpp), valid after begin(): its
// first phase joins the accumulator's last one (it reads only impulses), its
// last ends with a sync; summer() is the SumInto a LaunchExec running it needs.
template <class Tag, class Device, class T>
class Momentum {
 public:
  template <class BV, class CV>
  void begin(const BV&, const CV&, VectorD2View<T>, stream_t) {}
  template <class BV, class CV>
  void after_iteration(const BV&, const CV&, VectorD2View<T>, stream_t) {}
  template <class BV, class CV>
  detail::NoStep program(const BV&, const CV&, VectorD2View<T>) {
    return {};
  }
  SumInto<Device, T>* summer() { return nullptr; }
};

namespace detail {

// state = {theta, beta, restart test}: Nesterov's sequence theta_{k+1} solving
// theta_{k+1}^2 = (1 - theta_{k+1}) theta_k^2, beta = theta_k (1 - theta_k) /
// (theta_k^2 + theta_{k+1}); a step that went uphill (gradient . step > 0)
// restarts it (O'Donoghue and Candes 2015, "Adaptive restart for accelerated
// gradient schemes"), as Mazhar et al. 2015 do in APGD.
template <class T>
struct UpdateMomentum {
  T* state;
  GPUSOLVE_HD void operator()(std::size_t) const {
    const T theta = state[0];
    if (!(state[2] <= T(0))) {  // uphill, or not finite: restart
      state[0] = T(1), state[1] = T(0);
      return;
    }
    const T t2 = theta * theta;
    const T next = (-t2 + std::sqrt(t2 * t2 + 4 * t2)) / 2;
    state[1] = theta * (T(1) - theta) / (t2 + next);
    state[0] = next;
  }
};

// The gradient restart test: sum over contacts of rhs . (x_{k+1} - x_k).
template <class CV, class T>
struct StepAlongGradient {
  CV c;
  VectorD2View<T> rhs, px;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    T s = 0;
    for (std::size_t r = 0; r < px.size_y(); ++r) s += rhs(i, r) * (c.x(i, r) - px(i, r));
    return s;
  }
};

// y = x + beta (x - x_prev) for the impulses and, since velocities are affine
// in the impulses, for the moving bodies' velocities; x is kept as x_prev.
template <class BV, class CV, class T>
struct Extrapolate {
  BV b;
  CV c;
  VectorD2View<T> px, pv, pw;
  const T* state;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const T beta = state[1];
    if (i < c.size())
      for (std::size_t r = 0; r < px.size_y(); ++r) {
        const T x = c.x(i, r);
        c.x(i, r) = x + beta * (x - px(i, r));
        px(i, r) = x;
      }
    if (i < b.size() && b.moving(i))
      for (std::size_t k = 0; k < 3; ++k) {
        const T v = b.v(i, k), w = b.w(i, k);
        b.v(i, k) = v + beta * (v - pv(i, k));
        b.w(i, k) = w + beta * (w - pw(i, k));
        pv(i, k) = v, pw(i, k) = w;
      }
  }
};

// One momentum step: the restart test's sum, theta and beta (the one thread
// that reads the sum at once), the extrapolation.
template <class BV, class CV, class T>
struct NesterovStep {
  StepAlongGradient<CV, T> gradient;
  UpdateMomentum<T> update;
  Extrapolate<BV, CV, T> extrapolate;
  GPUSOLVE_EXEC_CHECK_DISABLE
  template <class E>
  GPUSOLVE_HD void operator()(const E& e) const {
    e.sum(extrapolate.c.size(), gradient, update.state + 2);
    e.each(1, update);
    e.sync();
    const std::size_t nc = extrapolate.c.size(), nb = extrapolate.b.size();
    e.each(nc > nb ? nc : nb, extrapolate);
    e.sync();
  }
};

// Keeps the start of an attempt as x_prev and sets theta = 1 (Extrapolate with beta 0).
template <class T>
struct ResetMomentum {
  T* state;
  GPUSOLVE_HD void operator()(std::size_t) const { state[0] = T(1), state[1] = T(0), state[2] = T(0); }
};

}  // namespace detail

// Nesterov momentum: the iterate the next Jacobi step starts from is extrapolated
// past the last one. Its scalars stay in the backend's memory (no host wait per iteration).
template <class Device, class T>
class Momentum<Nesterov, Device, T> {
 public:
  template <class BV, class CV>
  void begin(const BV& b, const CV& c, VectorD2View<T> rhs, stream_t stream) {
    detail::ensure_size(px_, c.size(), c.x.size_y());
    detail::ensure_size(pv_, b.size(), 3);
    detail::ensure_size(pw_, b.size(), 3);
    if (state_.size_x() == 0) state_.resize(3);
    // Sized here, so that after_iteration allocates nothing (it may be captured into a graph).
    sum_.reserve(c.size(), detail::StepAlongGradient<CV, T>{c, rhs, px_.view()}, state_.data() + 2);
    launch(Device{}, 1, detail::ResetMomentum<T>{state_.data()}, stream);
    const std::size_t n = c.size() > b.size() ? c.size() : b.size();
    launch(Device{}, n, program(b, c, rhs).extrapolate, stream);  // beta 0: records the start as x_prev
  }
  template <class BV, class CV>
  void after_iteration(const BV& b, const CV& c, VectorD2View<T> rhs, stream_t stream) {
    program(b, c, rhs)(detail::LaunchExec<Device, T>{stream, &sum_});
  }
  template <class BV, class CV>
  detail::NesterovStep<BV, CV, T> program(const BV& b, const CV& c, VectorD2View<T> rhs) {
    return {{c, rhs, px_.view()}, {state_.data()}, {b, c, px_.view(), pv_.view(), pw_.view(), state_.data()}};
  }
  SumInto<Device, T>* summer() { return &sum_; }

 private:
  VectorD2<T, device_is<Device>> px_, pv_, pw_;
  VectorD1<T, device_is<Device>> state_;
  SumInto<Device, T> sum_;
};

}  // namespace gpusolve::rbd
