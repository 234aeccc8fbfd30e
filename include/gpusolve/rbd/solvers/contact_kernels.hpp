// The per-contact work shared by the Jacobi solver and the Gauss-Seidel reference:
// inverse diagonal blocks, the next gap/velocity error (CalcNextPhi), the projected
// block update (ResolveCollisions) and the LCP residual.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"

namespace gpusolve::rbd {

namespace detail {

// The contact frame: row 0 is n, rows 1 and 2 (models with friction) t and o.
template <class T, class Model, class CV>
struct Frame {
  math::Vector3<T> q[Model::rows];
  GPUSOLVE_HD Frame(const CV& c, std::size_t i) {
    q[0] = math::load3<T>(c.n, i);
    if constexpr (Model::rows == 3) {
      q[1] = math::load3<T>(c.t, i);
      q[2] = math::load3<T>(c.o, i);
    }
  }
  // Q x: the impulse in world coordinates.
  GPUSOLVE_HD math::Vector3<T> world(const T* x) const {
    math::Vector3<T> p = q[0] * x[0];
    for (std::size_t r = 1; r < Model::rows; ++r) p += q[r] * x[r];
    return p;
  }
};

// Velocity of the material point at offset r: v + w x r.
template <class T>
GPUSOLVE_HD math::Vector3<T> point_velocity(const math::Vector3<T>& v, const math::Vector3<T>& w,
                                            const math::Vector3<T>& r) {
  return v + w % r;
}

// What a contact's velocity response needs of its two bodies: their indices,
// whether each moves, the contact's offsets, the inverse masses and inertias.
// Loaded apart from the response so that a caller can issue these loads before
// it computes the impulse (JacobiContact): issued after it, they are a round
// trip of their own in every iteration.
template <class T>
struct ContactBodies {
  std::uint32_t ia, ib;
  bool move_a, move_b;
  T ma, mb;
  math::Vector3<T> ra, rb;
  math::Matrix3x3<T> Ia, Ib;
  template <class BV, class CV>
  GPUSOLVE_HD ContactBodies(const BV& b, const CV& c, std::size_t i)
      : ia(c.a[i]), ib(c.b[i]), move_a(b.moving(ia)), move_b(b.moving(ib)), ma(b.inv_mass[ia]),
        mb(b.inv_mass[ib]), ra(math::load3<T>(c.ra, i)), rb(math::load3<T>(c.rb, i)), Ia(math::load9<T>(b.inv_inertia, ia)),
        Ib(math::load9<T>(b.inv_inertia, ib)) {}
};

// The velocity changes of a contact's two bodies caused by impulse p (world
// coordinates) acting on a and -p on b at the contact's points, and whether
// each body moves (a fixed body takes no change).
template <class T>
struct BodyResponse {
  std::uint32_t ia, ib;
  bool move_a, move_b;
  math::Vector3<T> ra, rb, dva, dwa, dvb, dwb;
  GPUSOLVE_HD BodyResponse(const ContactBodies<T>& k, const math::Vector3<T>& p)
      : ia(k.ia), ib(k.ib), move_a(k.move_a), move_b(k.move_b), ra(k.ra), rb(k.rb) {
    dva = k.ma * p, dwa = k.Ia * (ra % p);
    dvb = -(k.mb * p), dwb = -(k.Ib * (rb % p));
  }
  // Everything loaded here, each mass and inertia where it is used. The same
  // formulas as above: written through a shared helper, they gave the APGD
  // kernel 103 registers instead of 80.
  template <class BV, class CV>
  GPUSOLVE_HD BodyResponse(const BV& b, const CV& c, std::size_t i, const math::Vector3<T>& p)
      : ia(c.a[i]), ib(c.b[i]), move_a(b.moving(ia)), move_b(b.moving(ib)), ra(math::load3<T>(c.ra, i)),
        rb(math::load3<T>(c.rb, i)) {
    dva = b.inv_mass[ia] * p, dwa = math::load9<T>(b.inv_inertia, ia) * (ra % p);
    dvb = -(b.inv_mass[ib] * p), dwb = -(math::load9<T>(b.inv_inertia, ib) * (rb % p));
  }
  // Hands contact i's changes to the sink: Sink::add(i, response) applies or
  // records those of the moving bodies.
  template <class Sink>
  GPUSOLVE_HD void send(const Sink& sink, std::size_t i) const {
    sink.add(i, *this);
  }
};

// Where ResolveCollisions::update takes a contact's bodies from: a
// ContactBodies its caller loaded, or LoadBodies, loaded where the response
// needs them, after the impulse (fewer registers live across the update).
struct LoadBodies {};
template <class T, class BV, class CV>
GPUSOLVE_HD BodyResponse<T> response_of(const LoadBodies&, const BV& b, const CV& c, std::size_t i,
                                        const math::Vector3<T>& p) {
  return BodyResponse<T>(b, c, i, p);
}
template <class T, class BV, class CV>
GPUSOLVE_HD BodyResponse<T> response_of(const ContactBodies<T>& k, const BV&, const CV&, std::size_t,
                                        const math::Vector3<T>& p) {
  return BodyResponse<T>(k, p);
}

// Applies a contact's velocity change to its body at once: what makes a
// sweep Gauss-Seidel (each contact sees the updates of the contacts before it).
// Safe in parallel only over contacts that share no moving body (a colour).
template <class BV, class T>
struct DirectSink {
  BV b;
  GPUSOLVE_HD void add(std::size_t, const BodyResponse<T>& d) const {
    if (d.move_a) apply(d.ia, d.dva, d.dwa);
    if (d.move_b) apply(d.ib, d.dvb, d.dwb);
  }
  GPUSOLVE_HD void apply(std::uint32_t body, const math::Vector3<T>& dv, const math::Vector3<T>& dw) const {
    for (std::size_t k = 0; k < 3; ++k) b.v(body, k) += dv[k], b.w(body, k) += dw[k];
  }
};

}  // namespace detail

// The contact's step dinv from its own diagonal block W = Q^T (K_a + K_b) Q
// with, per body, K p = m^-1 p + (I^-1 (r x p)) x r (= (m^-1 E - r× I^-1 r×) p),
// projected to the model's rows. Fixed bodies contribute nothing (zero inverse
// mass and inertia). Run once per step, after collision detection.
// dinv is diagonal, and stored as its diagonal (one value per row): the normal
// row steps by 1 / W_nn, both friction rows by one scalar, 1 / max(W_tt, W_oo).
// A fixed point of x = proj(x - D r) solves the contact problem only where D
// keeps the cone's geometry: with the full W^-1, the normal and friction rows
// of a point off a body's centre line (a box's corner) are coupled, and the
// fixed point let a sliding box's four points each push sideways and lift it
// (issue 35: 13% too little friction on a slope, a hop on a floor). For a
// sphere W is already diagonal with equal friction rows, and the step is the same.
// With `scale`, dinv is multiplied by *scale: the projected update's step is
// omega dinv, so a retry at a smaller omega can scale the blocks instead of
// rebuilding an iteration (JacobiSolver; by a power of two the same bits).
// The k points of one body pair's manifold (a box face on a face: four,
// nearly parallel) act on the same two bodies almost as one constraint, so
// under a simultaneous (Jacobi-type) update each takes 1/k of the step: all k
// at once would apply the pair's correction k times over, which a Jacobi
// iteration does not survive (the shared cube pile diverged within 500 steps).
// A sweep that updates one point at a time (Gauss-Seidel) sees the others'
// changes and takes whole steps (`shared` false). A pair with one point, as
// every sphere pair, is unchanged.
template <class Model, class BV, class CV, class T>
struct InverseBlocks {
  BV b;
  CV c;
  const T* scale = nullptr;
  bool shared = true;  // a pair's k points take 1/k of a step each
  GPUSOLVE_HD void operator()(std::size_t i) const {
    constexpr std::size_t R = Model::rows;
    const detail::Frame<T, Model, CV> f(c, i);
    const std::uint32_t ids[2] = {c.a[i], c.b[i]};
    const math::Vector3<T> rs[2] = {math::load3<T>(c.ra, i), math::load3<T>(c.rb, i)};
    T W[R][R] = {};
    for (int s = 0; s < 2; ++s) {
      const std::uint32_t k = ids[s];
      const T im = b.inv_mass[k];
      const math::Matrix3x3<T> Iinv = math::load9<T>(b.inv_inertia, k);
      for (std::size_t col = 0; col < R; ++col) {
        const math::Vector3<T> Kq = im * f.q[col] + (Iinv * (rs[s] % f.q[col])) % rs[s];
        for (std::size_t row = 0; row < R; ++row) W[row][col] += math::dot(f.q[row], Kq);
      }
    }
    const T s = (scale ? *scale : T(1)) / (shared ? T(pair_points(i)) : T(1));
    c.dinv(i, 0) = s / W[0][0];
    if constexpr (R == 3) c.dinv(i, 1) = c.dinv(i, 2) = s / (W[1][1] > W[2][2] ? W[1][1] : W[2][2]);
  }
  // The contacts of contact i's body pair: its neighbours in the (a, b) order
  // with the same bodies (a manifold's up to max_manifold_points; a compound's
  // part pairs may add more, and take their shares alike).
  GPUSOLVE_HD std::uint32_t pair_points(std::size_t i) const {
    const std::size_t n = c.size();
    const std::uint32_t a = c.a[i], b = c.b[i];
    std::uint32_t k = 1;
    for (std::size_t j = i; j > 0 && c.a[j - 1] == a && c.b[j - 1] == b; --j) ++k;
    for (std::size_t j = i + 1; j < n && c.a[j] == a && c.b[j] == b; ++j) ++k;
    return k;
  }
};

// CalcNextPhi (thesis Algorithm 1): the contact-space error of the current
// velocities, rhs = Q^T (va + wa x ra - vb - wb x rb) + (phi / dt, 0, 0).
// The normal row asks for a gap rate of at least -phi0/dt: a contact still
// open by phi0 may close within the step but no further (it is not pushed
// apart early). A penetration (phi0 < 0) is removed only by the fraction
// `correction` per step: removing it all at once turns a deep contact into a
// separation speed of |phi0|/dt, which throws bodies out of a pile. A contact
// that bounces (restitution: c.bounce > 0, set by detection for an impact
// within the step) asks for exactly that separation speed instead, with no
// position correction on top, which would add energy to the bounce.
template <class Model, class BV, class CV, class T>
struct CalcNextPhi {
  BV b;
  CV c;
  VectorD2View<T> rhs;  // n x rows
  T inv_dt;
  T correction = T(1);
  GPUSOLVE_HD void operator()(std::size_t i) const {
    T e[Model::rows];
    error(i, e);
    for (std::size_t r = 0; r < Model::rows; ++r) rhs(i, r) = e[r];
  }
  // Contact i's error at the velocities `it` gives (iterate.hpp), computed without writing it.
  template <class Iterate = detail::CurrentIterate<T>>
  GPUSOLVE_HD void error(std::size_t i, T* e, const Iterate& it = Iterate{}) const {
    const detail::Frame<T, Model, CV> f(c, i);
    const std::uint32_t ia = c.a[i], ib = c.b[i];
    math::Vector3<T> va, wa, vb, wb;
    it.velocity(b, ia, va, wa);
    it.velocity(b, ib, vb, wb);
    const math::Vector3<T> du = detail::point_velocity(va, wa, math::load3<T>(c.ra, i)) -
                                detail::point_velocity(vb, wb, math::load3<T>(c.rb, i));
    for (std::size_t r = 0; r < Model::rows; ++r) e[r] = math::dot(f.q[r], du);
    const T phi0 = c.phi0[i], bounce = c.bounce[i], approach = e[0];
    e[0] += (phi0 < T(0) ? correction * phi0 : phi0) * inv_dt;  // as without restitution, to the bit
    if (bounce > T(0)) e[0] = approach - bounce;
  }
};

// ResolveCollisions (thesis Algorithm 1): the projected, under-relaxed block
// update x' = proj(x - omega Dinv rhs), and the body velocity changes it causes,
// handed to Sink::add(i, response) (detail::BodyResponse). Sink decides how
// the changes of the moving bodies reach them.
//
// THE LCP RESIDUAL (defined here, once): with measure set, residual[i] is the
// largest component, in the contact frame, of the change of the relative
// velocity at contact i caused by contact i's own projected update in this
// iteration, |Q^T W Q (x' - x)|_inf, in m/s; the solver's residual is its maximum
// over contacts. It is zero exactly at a fixed point of the projected iteration
// (a solution of the LCP) and says by how much the next projected step would
// still change a contact velocity. A NaN or infinite value is stored as +inf,
// so the maximum reports it.
template <class Model, class BV, class CV, class Sink, class T>
struct ResolveCollisions {
  BV b;
  CV c;
  VectorD2View<T> rhs;
  Sink sink;
  T omega;
  bool measure;
  VectorD1View<T> residual;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    T e[Model::rows];
    for (std::size_t r = 0; r < Model::rows; ++r) e[r] = rhs(i, r);
    update(i, e);
  }
  // The update from contact i's error e, starting from the impulse `it` gives
  // (iterate.hpp), with the bodies `bodies` names (detail::response_of). The new
  // x is stored only after the body response was computed and sent: the
  // compiler may not move a load past a store (the views might alias), so
  // storing first would make the response's loads wait for it.
  template <class Iterate = detail::CurrentIterate<T>, class Bodies = detail::LoadBodies>
  GPUSOLVE_HD void update(std::size_t i, const T (&e)[Model::rows], const Iterate& it = Iterate{},
                          const Bodies& bodies = Bodies{}) const {
    constexpr std::size_t R = Model::rows;
    const detail::Frame<T, Model, CV> f(c, i);
    T x0[R], y[R], x[R], dx[R];
    it.start(c, i, x0, y);
    for (std::size_t r = 0; r < R; ++r) x[r] = y[r] - omega * (c.dinv(i, r) * e[r]);
    T mu = T(0);
    if constexpr (Model::friction) mu = c.mu[i];
    Model::project(x, mu);
    for (std::size_t r = 0; r < R; ++r) dx[r] = x[r] - y[r];
    const detail::BodyResponse<T> d = detail::response_of<T>(bodies, b, c, i, f.world(dx));
    d.send(sink, i);
    it.store(c, i, e, x0, x);
    if (measure) {
      const math::Vector3<T> du =
          detail::point_velocity(d.dva, d.dwa, d.ra) - detail::point_velocity(d.dvb, d.dwb, d.rb);
      T m = 0;
      bool finite = true;
      for (std::size_t r = 0; r < R; ++r) {
        const T e = std::fabs(math::dot(f.q[r], du));
        finite = finite && e <= std::numeric_limits<T>::max();  // false for NaN and inf
        m = e > m ? e : m;
      }
      residual[i] = finite ? m : std::numeric_limits<T>::infinity();
    }
  }
};

// One Jacobi iteration's work on contact i in one kernel: its velocity error,
// then its projected update, both at the iterate `iterate` gives. The update
// reads only contact i's own error, and the velocities it reads change only
// after the kernel (Sink accumulates), so fusing saves a launch and a pass over
// rhs without changing a bit; the error stays in registers. Where the
// iterate says so (Iterate::bodies_first, iterate.hpp), the bodies' masses and
// inertias are loaded first, with the velocities, instead of after the impulse.
template <class Model, class BV, class CV, class Sink, class T, class Iterate = detail::CurrentIterate<T>>
struct JacobiContact {
  CalcNextPhi<Model, BV, CV, T> phi;
  ResolveCollisions<Model, BV, CV, Sink, T> resolve;
  Iterate iterate;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    T e[Model::rows];
    if constexpr (Iterate::bodies_first) {
      const detail::ContactBodies<T> bodies(resolve.b, resolve.c, i);
      phi.error(i, e, iterate);
      resolve.update(i, e, iterate, bodies);
    } else {
      phi.error(i, e, iterate);
      resolve.update(i, e, iterate);
    }
  }
};

// ApplyImpulses: the body velocity changes of the impulses already in c.x
// (J^T x through the same sink as ResolveCollisions), so that velocities and
// impulses agree before a solve that starts from a nonzero x (warm start).
template <class Model, class BV, class CV, class Sink, class T>
struct ApplyImpulses {
  BV b;
  CV c;
  Sink sink;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    T x[Model::rows];
    for (std::size_t r = 0; r < Model::rows; ++r) x[r] = c.x(i, r);
    const detail::Frame<T, Model, CV> f(c, i);
    detail::BodyResponse<T>(b, c, i, f.world(x)).send(sink, i);
  }
};

}  // namespace gpusolve::rbd
