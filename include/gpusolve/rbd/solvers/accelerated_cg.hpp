// AcceleratedCG: conjugate-gradient steps on the contacts inside their friction
// cone while the active set holds, APGD steps while it changes.
//
// The cone-friction contact problem is the convex QP
//   min 1/2 x^T W x + x^T r,  x_i in K_i (x_n >= 0, |x_t| <= mu x_n),
// whose gradient g = W x + r is each contact's velocity error (CalcNextPhi)
// at v = v0 + M^-1 J^T x. The method follows MPRGP (Dostal and Schoberl 2005,
// "Minimizing quadratic functions subject to bound constraints with the rate of
// convergence and finite termination", Comput. Optim. Appl. 30; Dostal and
// Kozubek 2012 for separable convex constraints such as cones), with APGD
// (Mazhar, Heyn, Negrut and Tasora 2015, ACM TOG 34(3); jacobi.hpp) in place of
// MPRGP's expansion step:
//  - the free set F holds the contacts strictly inside their cone; while the
//    iterate is proportional (the projected Jacobi steps of the contacts outside
//    F are small against the free gradient, chop <= gamma^2 g_F^T Dinv g_F, gamma
//    0.1), a CG step on F preconditioned by each contact's inverse block: exact
//    line search along p, capped at the largest step that stays in the cones;
//  - after a truncated CG step (the active set is changing) APGD steps for a
//    hold of 1, 2, 4 ... 32 iterations, doubling with each truncation, back to 1
//    after a full CG step; otherwise whenever the iterate is not proportional;
//  - an APGD step is one projected Jacobi step from Nesterov's extrapolation,
//    restarted when it goes uphill (UpdateMomentum) and after a CG step.
// W p is never formed: J^T p goes through the Gather accumulator's update cache
// into per-body sums M^-1 J^T p, and p^T W p is their M-norm. The gradient is
// recomputed from the velocities at every iteration's direction and at every
// check. An iteration that measures the residual takes no momentum (beta 0), so
// the impulses it leaves lie in their cones and agree with the velocities: the
// solve may stop there. Scalars stay in the backend's memory; the host reads
// only the residual at checks. It is for mass ratios APGD converges slowly on
// (a 1:1000 column, tests/host/test_rbd_methods.cpp; docs/tuning/solve.md).
// ConeFriction only. Runs distributed (set_exchange): its sums over contacts
// and bodies and its residual are reduced over the ranks, the bodies'
// direction sums combined; a shadow's p^T W p is its owner's to count.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/contact_models/cone_friction.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/accumulation.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/contact_solver_base.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"
#include "gpusolve/rbd/solvers/momentum.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail::acg {

// The method's scalars, in backend memory. The last momentum_slots hold
// Nesterov's sequence in UpdateMomentum's layout (momentum.hpp).
enum : std::size_t {
  rz_slot,         // sum over F of g^T Dinv g (the classification's gradient)
  chop_slot,       // sum over the rest of the chopped step's energy / omega^2
  rz_prev_slot,    // rz of the last CG step
  cg_beta_slot,    // CG's beta
  mode_slot,       // 1: this iteration takes a CG step, 0: an APGD step
  restart_slot,    // 1: the next CG step starts from steepest descent
  alpha_max_slot,  // the largest feasible CG step
  pwp_slot,        // p^T W p
  alpha_slot,      // the step taken
  descent_slot,    // -g^T p
  prev_mode_slot,  // the last iteration's mode
  truncated_slot,  // 1: the last CG step was cut at the feasible step
  hold_slot,       // APGD steps still forced
  backoff_slot,    // the next hold
  momentum_slot,
  slots = momentum_slot + momentum_slots
};

// Strictly inside the cone, by a relative margin (a contact on the rim is not free).
template <class T>
GPUSOLVE_HD bool is_free(const T* x, T mu) {
  if (!(x[0] > T(0))) return false;
  return std::sqrt(x[1] * x[1] + x[2] * x[2]) < mu * x[0] * T(1 - 1e-4);
}

// The largest t >= 0 with x + t p in the cone, x strictly inside. In double, on
// x and p scaled by 1 / max(x_n, |p|) (t is unchanged), so that impulses near
// the apex neither underflow nor overflow; the result is verified (the point
// just short of t, or the direction where t is infinite, must be admissible)
// and 0 is returned where it fails, which truncates the CG step.
template <class T>
GPUSOLVE_HD T feasible_step(const T* xi, const T* pi, T mu_) {
  using D = double;
  const D inf = std::numeric_limits<D>::infinity();
  D m = D(xi[0]);
  for (int r = 0; r < 3; ++r) m = std::fabs(D(pi[r])) > m ? std::fabs(D(pi[r])) : m;
  if (!(m > D(0))) return T(0);
  const D sc = D(1) / m, mu = D(mu_);
  const D x[3] = {D(xi[0]) * sc, D(xi[1]) * sc, D(xi[2]) * sc};
  const D p[3] = {D(pi[0]) * sc, D(pi[1]) * sc, D(pi[2]) * sc};
  D t = p[0] < D(0) ? -x[0] / p[0] : inf;
  // |x_t + s p_t|^2 = mu^2 (x_n + s p_n)^2: a s^2 + 2 bb s + cc = 0, cc < 0.
  const D m2 = mu * mu;
  const D a = p[1] * p[1] + p[2] * p[2] - m2 * p[0] * p[0];
  const D bb = x[1] * p[1] + x[2] * p[2] - m2 * x[0] * p[0];
  const D cc = x[1] * x[1] + x[2] * x[2] - m2 * x[0] * x[0];
  D r = inf;
  if (a == D(0)) {
    if (bb > D(0)) r = -cc / (2 * bb);
  } else {
    const D disc = bb * bb - a * cc;
    if (disc >= D(0)) {
      const D sq = std::sqrt(disc);
      const D q = bb >= D(0) ? -(bb + sq) : -(bb - sq);  // roots q / a and cc / q, without cancellation
      const D r1 = q / a, r2 = q != D(0) ? cc / q : inf;
      const D lo = r1 < r2 ? r1 : r2, hi = r1 < r2 ? r2 : r1;
      r = lo > D(0) ? lo : (hi > D(0) ? hi : inf);
    }
  }
  t = r < t ? r : t;
  if (t < inf) {
    const D s = t * D(1 - 1e-6);
    const D n = x[0] + s * p[0], u = x[1] + s * p[1], v = x[2] + s * p[2];
    if (!(n >= D(0)) || !(std::sqrt(u * u + v * v) <= mu * n + D(1e-9))) return T(0);
  } else if (!(p[0] >= D(0)) || !(std::sqrt(p[1] * p[1] + p[2] * p[2]) <= mu * p[0])) {
    return T(0);
  }
  return t < D(std::numeric_limits<T>::max()) ? T(t) : std::numeric_limits<T>::infinity();
}

// An iterate for ResolveCollisions::update that starts from the impulse as it
// is and keeps nothing: the update only measures (the residual at a check).
template <class T>
struct Probe : CurrentIterate<T> {
  template <class CV, std::size_t R>
  GPUSOLVE_HD void store(const CV&, std::size_t, const T (&)[R], const T (&)[R], const T (&)[R]) const {}
};

// A sink that drops the velocity changes (with Probe: measuring only).
struct NoSink {
  template <class T>
  GPUSOLVE_HD void add(std::size_t, const BodyResponse<T>&) const {}
};

// The APGD step's store: the new impulse, no CG direction, and the contact's
// term of the restart test, e . (x_{k+1} - x_k) (x_k in px).
template <class T>
struct ApgdStore : CurrentIterate<T> {
  VectorD2View<T> p, px;
  VectorD1View<T> uphill;
  template <class CV, std::size_t R>
  GPUSOLVE_HD void store(const CV& c, std::size_t i, const T (&e)[R], const T (&)[R], const T (&x)[R]) const {
    T s = 0;
    for (std::size_t r = 0; r < R; ++r) {
      s += e[r] * (x[r] - px(i, r));
      c.x(i, r) = x[r], p(i, r) = T(0);
    }
    uphill[i] = s;
  }
};

// The classification from the gradient g: z = Dinv g and rz = g^T z on a free
// contact; elsewhere the chopped step's energy dx^T W_ii dx / omega^2 (dx the
// projected Jacobi step), or +inf for an impulse outside its cone (an
// extrapolated APGD iterate may not take a CG step). `recompute`: g from the
// velocities (stored in rhs), else the recurrence's g from rhs. `measure`: the
// library's residual (ResolveCollisions with measure set) at this iterate.
template <class Model, class BV, class CV, class T>
struct Classify {
  CalcNextPhi<Model, BV, CV, T> phi;  // b, c, rhs
  VectorD1View<T> rz, chop, residual;
  T omega;
  GPUSOLVE_HD void run(std::size_t i, bool recompute, bool measure) const {
    constexpr std::size_t R = Model::rows;
    const CV& c = phi.c;
    T e[R], x[R];
    if (recompute) {
      phi.error(i, e);
      for (std::size_t r = 0; r < R; ++r) phi.rhs(i, r) = e[r];
    } else {
      for (std::size_t r = 0; r < R; ++r) e[r] = phi.rhs(i, r);
    }
    for (std::size_t r = 0; r < R; ++r) x[r] = c.x(i, r);
    const T mu = c.mu[i];
    if (is_free(x, mu)) {
      T s = 0;
      for (std::size_t r = 0; r < R; ++r) s += (c.dinv(i, r) * e[r]) * e[r];
      rz[i] = s, chop[i] = T(0);
    } else {
      T xp[R], dx[R];
      for (std::size_t r = 0; r < R; ++r) xp[r] = x[r];
      Model::project(xp, ContactLimits<T>{mu});
      bool outside = false;
      for (std::size_t r = 0; r < R; ++r)
        outside = outside || std::fabs(xp[r] - x[r]) > T(1e-6) * (std::fabs(x[0]) + T(1e-30));
      for (std::size_t r = 0; r < R; ++r) dx[r] = x[r] - omega * (c.dinv(i, r) * e[r]);
      Model::project(dx, ContactLimits<T>{mu});
      for (std::size_t r = 0; r < R; ++r) dx[r] -= x[r];
      const detail::Frame<T, Model, CV> f(c, i);
      const detail::BodyResponse<T> d(phi.b, c, i, f.linear(dx));
      const math::Vector3<T> du =
          detail::point_velocity(d.dva, d.dwa, d.ra) - detail::point_velocity(d.dvb, d.dwb, d.rb);
      T s = 0;
      for (std::size_t r = 0; r < R; ++r) s += dx[r] * math::dot(f.q[r], du);
      rz[i] = T(0), chop[i] = outside ? std::numeric_limits<T>::infinity() : s / (omega * omega);
    }
    if (measure)
      ResolveCollisions<Model, BV, CV, NoSink, T>{phi.b, c, phi.rhs, NoSink{}, omega, true, residual}.update(
          i, e, Probe<T>{});
  }
};

template <class Model, class BV, class CV, class T>
struct ClassifyPass {
  Classify<Model, BV, CV, T> cl;
  bool measure;
  GPUSOLVE_HD void operator()(std::size_t i) const { cl.run(i, true, measure); }
};

// The contact phase: the gradient e from the velocities (kept in rhs), then
// CG: p = -Dinv e + beta p on F (0 elsewhere), -e . p for the line search and
// the feasible step, J^T p to the sink; APGD: one projected Jacobi step from e
// (ResolveCollisions), its J^T dx to the sink, and the restart test's term.
template <class Model, class BV, class CV, class Sink, class T>
struct Direction {
  CalcNextPhi<Model, BV, CV, T> phi;
  ResolveCollisions<Model, BV, CV, Sink, T> jacobi;
  VectorD2View<T> p, px;
  VectorD1View<T> step, uphill, descent;
  const T* state;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    constexpr std::size_t R = Model::rows;
    const CV& c = phi.c;
    T e[R];
    phi.error(i, e);
    for (std::size_t r = 0; r < R; ++r) phi.rhs(i, r) = e[r];
    if (!(state[mode_slot] > T(0))) {
      jacobi.update(i, e, ApgdStore<T>{{}, p, px, uphill});
      step[i] = std::numeric_limits<T>::infinity(), descent[i] = T(0);
      return;
    }
    T x[R], d[R];
    for (std::size_t r = 0; r < R; ++r) x[r] = c.x(i, r);
    const T mu = c.mu[i], beta = state[cg_beta_slot];
    const bool free = is_free(x, mu);
    T s = 0;
    for (std::size_t r = 0; r < R; ++r) {
      const T z = c.dinv(i, r) * e[r];
      d[r] = free ? -z + beta * p(i, r) : T(0);
      p(i, r) = d[r];
      s -= e[r] * d[r];
    }
    step[i] = free ? feasible_step(x, d, mu) : std::numeric_limits<T>::infinity();
    uphill[i] = T(0), descent[i] = s;
    const detail::Frame<T, Model, CV> f(c, i);
    detail::BodyResponse<T>(phi.b, c, i, f.linear(d)).send(jacobi.sink, i);
  }
};

// The body phase, as the iterate whose add() the Gather accumulator calls with
// each body's summed change s: dvp = s and its M-norm (for p^T W p); an APGD
// step also adds s to the velocities.
template <class T>
struct BodyDirection {
  VectorD2View<T> dvp, dwp;
  VectorD1View<T> pwp;
  const T* state;
  template <class BV>
  GPUSOLVE_HD void add(const BV& b, std::size_t k, const T (&sv)[3], const T (&sw)[3]) const {
    pwp[k] = T(0);
    if (!b.moving(k)) {
      for (std::size_t c = 0; c < 3; ++c) dvp(k, c) = T(0), dwp(k, c) = T(0);
      return;
    }
    for (std::size_t c = 0; c < 3; ++c) dvp(k, c) = sv[c], dwp(k, c) = sw[c];
    if (state[mode_slot] > T(0)) {
      if (b.status[k] == shadow) return;  // its owner's rank counts it
      const math::Vector3<T> w(sw[0], sw[1], sw[2]);
      const math::Vector3<T> Iw = math::inverse_spd(math::load9<T>(b.inv_inertia, k)) * w;
      pwp[k] = (sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2]) / b.inv_mass[k] + math::dot(w, Iw);
    } else {
      for (std::size_t c = 0; c < 3; ++c) b.v(k, c) += sv[c], b.w(k, c) += sw[c];
    }
  }
};

// One thread: the CG step length (exact line search -g.p / p^T W p, cut at the
// feasible step, which marks the step truncated), or Nesterov's theta and beta,
// restarted after a CG step; no momentum in an iteration that measures.
template <class T>
struct StepLength {
  T* state;
  bool measure;
  GPUSOLVE_HD void operator()(std::size_t) const {
    T* momentum = state + momentum_slot;
    if (state[mode_slot] > T(0)) {
      const T pwp = state[pwp_slot], descent = state[descent_slot];
      T alpha = pwp > T(0) && descent > T(0) ? descent / pwp : T(0);
      if (!(alpha > T(0))) state[restart_slot] = T(1);
      if (!(alpha < state[alpha_max_slot]))
        alpha = state[alpha_max_slot], state[restart_slot] = T(1), state[truncated_slot] = T(1);
      state[alpha_slot] = alpha;
      momentum[beta_slot] = T(0);
      return;
    }
    state[alpha_slot] = T(1);
    if (state[prev_mode_slot] > T(0)) momentum[uphill_slot] = T(1);  // restart after a CG step
    UpdateMomentum<T>{momentum}(0);
    if (measure) momentum[beta_slot] = T(0);
  }
};

// Contacts and bodies: to the next iterate. CG: x += alpha p (projected for
// rounding only: the step is feasible), v += alpha dvp, g += alpha J dvp. APGD
// (x, v already at the projected step): the extrapolation of x, v and g by
// Nesterov's beta, the projected iterates kept in px, pv, pw, pg. Then the
// classification from this g unless the iteration measures (which classifies
// from the velocities afterwards).
template <class Model, class BV, class CV, class T>
struct Advance {
  Classify<Model, BV, CV, T> cl;
  VectorD2View<T> p, dvp, dwp, px, pg, pv, pw;
  const T* state;
  bool classify;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    constexpr std::size_t R = Model::rows;
    const BV& b = cl.phi.b;
    const CV& c = cl.phi.c;
    const bool cg = state[mode_slot] > T(0);
    const T alpha = state[alpha_slot], beta = state[momentum_slot + beta_slot];
    if (i < b.size() && b.moving(i))
      for (std::size_t k = 0; k < 3; ++k) {
        if (cg) {
          b.v(i, k) += alpha * dvp(i, k), b.w(i, k) += alpha * dwp(i, k);
        } else {
          const T v = b.v(i, k), w = b.w(i, k);
          b.v(i, k) = v + beta * (v - pv(i, k)), b.w(i, k) = w + beta * (w - pw(i, k));
          pv(i, k) = v, pw(i, k) = w;
        }
      }
    if (i >= c.size()) return;
    const detail::Frame<T, Model, CV> f(c, i);
    const std::uint32_t ia = c.a[i], ib = c.b[i];
    const math::Vector3<T> du =
        detail::point_velocity(math::load3<T>(dvp, ia), math::load3<T>(dwp, ia), math::load3<T>(c.ra, i)) -
        detail::point_velocity(math::load3<T>(dvp, ib), math::load3<T>(dwp, ib), math::load3<T>(c.rb, i));
    if (cg) {
      T x[R];
      bool moved = false;
      for (std::size_t r = 0; r < R; ++r) x[r] = c.x(i, r) + alpha * p(i, r), moved = moved || p(i, r) != T(0);
      if (moved) Model::project(x, limits_of<Model, T>(c, i));
      for (std::size_t r = 0; r < R; ++r) c.x(i, r) = x[r], cl.phi.rhs(i, r) += alpha * math::dot(f.q[r], du);
    } else {
      for (std::size_t r = 0; r < R; ++r) {
        const T g = cl.phi.rhs(i, r) + math::dot(f.q[r], du);  // at the projected iterate
        const T x = c.x(i, r);
        c.x(i, r) = x + beta * (x - px(i, r)), px(i, r) = x;
        cl.phi.rhs(i, r) = g + beta * (g - pg(i, r)), pg(i, r) = g;
      }
    }
    if (classify) cl.run(i, false, false);
  }
};

// One thread, after the classification's sums: the next mode. CG where the
// iterate is proportional (beta = rz / rz_prev, 0 after a restart), else APGD;
// a truncated CG step doubles the hold of forced APGD steps (up to max_hold), a
// full one resets it to 1.
template <class T>
struct Decide {
  T* state;
  T gamma2, max_hold;
  GPUSOLVE_HD void operator()(std::size_t) const {
    state[prev_mode_slot] = state[mode_slot];
    const T rz = state[rz_slot];
    if (rz > T(0) && state[chop_slot] <= gamma2 * rz) {
      const bool restart = state[restart_slot] > T(0) || !(state[rz_prev_slot] > T(0));
      state[cg_beta_slot] = restart ? T(0) : rz / state[rz_prev_slot];
      state[restart_slot] = T(0), state[rz_prev_slot] = rz, state[mode_slot] = T(1);
    } else {
      state[mode_slot] = T(0), state[restart_slot] = T(1), state[cg_beta_slot] = T(0);
    }
    if (state[truncated_slot] > T(0)) {
      const T next = 2 * state[backoff_slot];
      state[backoff_slot] = next > max_hold ? max_hold : next;
      state[hold_slot] = state[backoff_slot];
      state[truncated_slot] = T(0);
    } else if (state[prev_mode_slot] > T(0)) {
      state[backoff_slot] = T(1);
    }
    if (state[hold_slot] > T(0)) {
      state[hold_slot] -= T(1);
      state[mode_slot] = T(0), state[restart_slot] = T(1), state[cg_beta_slot] = T(0);
    }
  }
};

// One thread: an attempt's start (a CG step first, from steepest descent). The
// momentum's slots are ResetMomentum's.
template <class T>
struct ResetState {
  T* state;
  GPUSOLVE_HD void operator()(std::size_t) const {
    for (std::size_t k = 0; k < momentum_slot; ++k) state[k] = T(0);
    state[restart_slot] = T(1), state[mode_slot] = T(1), state[backoff_slot] = T(1);
  }
};

}  // namespace detail::acg

// Same contract as JacobiSolver::solve (solver.hpp): warm start applies J^T x
// first, a diverging solve is retried cold at a smaller omega (relaxation.hpp),
// the residual is the library's (contact_kernels.hpp) at every check_every-th
// iteration. omega scales the APGD steps' projected Jacobi step and the
// proportionality test; CG steps take their exact line search.
template <class Device, class T, class Model>
class AcceleratedCGSolver : public ContactSolverBase<Device, T, Model> {
  static_assert(std::is_same_v<Model, ConeFriction>,
                "AcceleratedCG solves the cone-friction problem only: use it with ConeFriction");
  using Base = ContactSolverBase<Device, T, Model>;

 public:
  static constexpr double default_omega = 0.3;  // APGD's (jacobi.hpp)
  static constexpr double gamma = 0.1;          // MPRGP's proportioning constant
  static constexpr double max_hold = 32;        // the longest run of APGD steps after a truncated CG step
  // Its residual checks where SolveSettings::check_every is 0, the thesis's
  // every 50: checked every 10 iterations (each check takes no momentum) and
  // stopped at the first under 5e-3, a settled 12-layer pyramid crept 1.1% of a
  // box's half extent in 2 s, within the test's 2e-4 at 50 (tests/host/test_rbd_shapes_physics.cpp).
  static constexpr std::size_t default_check_every = 50;

  // A distributed solve (rbd/distributed/): every sum and the residual are
  // reduced over the ranks through `exchange` (nullptr: none), and the bodies'
  // sums combined; a rank without contacts still takes part in each.
  void set_exchange(BodyExchange<T>* exchange) { exchange_ = exchange; }

  using typename Base::BodyStore;
  using typename Base::BV;
  using typename Base::ContactStore;
  using typename Base::CV;

  SolverStats<T> solve(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s,
                       stream_t stream = stream_t{}, bool from_x = false) {
    namespace acg = detail::acg;
    SolverStats<T> stats;
    const BV b = bodies.view();
    const CV c = contacts.view();
    if (!this->begin(b, c, s, stats, stream) && exchange_ == nullptr) return stats;  // a rank takes part, contacts or not
    const std::size_t nc = c.size(), nb = b.size(), n = nc > nb ? nc : nb;
    const Device dev{};
    acc_.prepare(b, c, stream);
    stats.reduction_passes = acc_.passes();
    reserve(nc, nb);
    T* state = state_.data();
    const auto rhs = rhs_.view();
    const auto residual = this->residual_.view();
    const CalcNextPhi<Model, BV, CV, T> phi{b, c, rhs, T(1) / s.dt, s.correction};
    const auto sum = [&](std::size_t count, const VectorD1View<T>& terms, std::size_t slot) {
      alg_.reduce_values(terms.ptr, count, T(0), detail::PlusOp{}, state + slot, stream);
      if (exchange_ != nullptr) exchange_->reduce(state + slot, ExchangeOp::sum, stream);
    };
    auto attempt = [&](T omega, SolverStats<T>& st) {
      start_attempt(b, c, contacts, from_x && st.retries == 0, stream);
      const acg::Classify<Model, BV, CV, T> cl{phi, rz_.view(), chop_.view(), residual, omega};
      const acg::Direction<Model, BV, CV, Sink, T> direction{
          phi,          {b, c, rhs, acc_.sink(), omega, false, residual}, p_.view(), px_.view(), step_.view(),
          uphill_.view(), descent_.view(), state};
      const auto body_phase = acc_.program(b, acg::BodyDirection<T>{dvp_.view(), dwp_.view(), pwp_.view(), state});
      acg::Advance<Model, BV, CV, T> advance{cl,         p_.view(),  dvp_.view(), dwp_.view(), px_.view(),
                                             pg_.view(), pv_.view(), pw_.view(),  state,       true};
      const acg::Decide<T> decide{state, T(gamma * gamma), T(max_hold)};
      auto classified = [&]() {
        sum(nc, rz_.view(), acg::rz_slot);
        sum(nc, chop_.view(), acg::chop_slot);
        launch(dev, 1, decide, stream);
      };
      launch(dev, nc, acg::ClassifyPass<Model, BV, CV, T>{cl, false}, stream);
      classified();
      SolverSettings<T> checks = s;
      if (checks.check_every == 0) checks.check_every = default_check_every;
      ConvergenceMonitor<T> monitor(checks, st);
      for (std::size_t it = 1;; ++it) {
        const bool measure = monitor.checks(it);
        launch(dev, nc, direction, stream);
        alg_.reduce_values(step_.data(), nc, std::numeric_limits<T>::infinity(), detail::MinOp{},
                           state + acg::alpha_max_slot, stream);
        if (exchange_ != nullptr) exchange_->reduce(state + acg::alpha_max_slot, ExchangeOp::minimum, stream);
        sum(nc, uphill_.view(), acg::momentum_slot + detail::uphill_slot);
        sum(nc, descent_.view(), acg::descent_slot);
        body_phase(launched(stream));
        sum(nb, pwp_.view(), acg::pwp_slot);
        launch(dev, 1, acg::StepLength<T>{state, measure}, stream);
        advance.classify = !measure;
        launch(dev, n, advance, stream);
        if (measure) launch(dev, nc, acg::ClassifyPass<Model, BV, CV, T>{cl, true}, stream);
        classified();
        if (measure && monitor.stop(it, this->residual(b, nc, stream, exchange_))) break;
      }
    };
    solve_relaxed(s, omega_of<AcceleratedCGSolver>(s), b, this->start_, stats, attempt, stream);
    return stats;
  }

 private:
  using Sink = decltype(std::declval<Accumulator<Gather, Device, T>&>().sink());

  detail::LaunchExec<Device, T> launched(stream_t stream) { return {stream, nullptr, exchange_}; }

  // Scratch for nc contacts and nb bodies, kept between solves.
  void reserve(std::size_t nc, std::size_t nb) {
    for (auto* v : {&rhs_, &p_, &px_, &pg_}) gpusolve::detail::ensure_size(*v, nc, Model::rows);
    for (auto* v : {&dvp_, &dwp_, &pv_, &pw_}) gpusolve::detail::ensure_size(*v, nb, 3);
    for (auto* v : {&rz_, &chop_, &step_, &uphill_, &descent_}) gpusolve::detail::ensure_size(*v, nc);
    gpusolve::detail::ensure_size(pwp_, nb);
    if (state_.size_x() == 0) state_.resize(detail::acg::slots);
  }

  // An attempt's start: from the impulses' velocity change (`warm`) or from
  // zero impulses, with no direction, momentum or scalar left from before.
  void start_attempt(const BV& b, const CV& c, ContactStore& contacts, bool warm, stream_t stream) {
    namespace acg = detail::acg;
    const Device dev{};
    if (warm) {
      launch(dev, c.size(), ApplyImpulses<Model, BV, CV, Sink, T>{b, c, acc_.sink()}, stream);
      acc_.program(b)(launched(stream));
    } else {
      contacts.x.fill(T(0), stream);
    }
    // No stale value may enter the first extrapolation (its beta is 0, but 0 * NaN is not 0).
    p_.fill(T(0), stream), pg_.fill(T(0), stream);
    const std::size_t n = c.size() > b.size() ? c.size() : b.size();
    T* state = state_.data();
    launch(dev, n, detail::ResetMomentum<BV, CV, T>{b, c, px_.view(), pv_.view(), pw_.view(), state + acg::momentum_slot},
           stream);
    launch(dev, 1, acg::ResetState<T>{state}, stream);
  }

  Accumulator<Gather, Device, T> acc_;
  detail::DeviceAlgorithms<Device> alg_;
  BodyExchange<T>* exchange_ = nullptr;  // set_exchange
  VectorD2<T, device_is<Device>> rhs_, p_, px_, pg_, dvp_, dwp_, pv_, pw_;  // rhs_: each contact's gradient
  VectorD1<T, device_is<Device>> rz_, chop_, step_, uphill_, descent_, pwp_, state_;
};

// The method tag (a model of the Solver concept, solver.hpp).
struct AcceleratedCG {
  template <class Device, class T, class Model>
  using solver = AcceleratedCGSolver<Device, T, Model>;
  static constexpr const char* name = "apgd-cg";
};

}  // namespace gpusolve::rbd
