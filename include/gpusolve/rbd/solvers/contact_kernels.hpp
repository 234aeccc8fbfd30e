// The per-contact work shared by the Jacobi solver and the Gauss-Seidel reference:
// inverse diagonal blocks, the next gap/velocity error (CalcNextPhi), the projected
// block update (ResolveCollisions) and the LCP residual.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"
#include "gpusolve/rbd/solvers/iterate.hpp"

namespace gpusolve::rbd {

namespace detail {

// The contact frame: row 0 is n, rows 1 and 2 (models with friction) t and o;
// a model's angular rows (from Model::linear_rows on) turn about n, t, o in turn.
template <class T, class Model, class CV>
struct Frame {
  static constexpr std::size_t R = Model::rows, L = Model::linear_rows;
  static_assert((L == 1 || L == 3) && (R == L || R == L + 3), "Frame: rows n[, t, o][, about n, t, o]");
  math::Vector3<T> q[L];
  GPUSOLVE_HD Frame(const CV& c, std::size_t i) {
    q[0] = math::load3<T>(c.n, i);
    if constexpr (L == 3) {
      q[1] = math::load3<T>(c.t, i);
      q[2] = math::load3<T>(c.o, i);
    }
  }
  // The linear impulse in world coordinates: the linear rows of Q x.
  GPUSOLVE_HD math::Vector3<T> linear(const T* x) const {
    math::Vector3<T> p = q[0] * x[0];
    for (std::size_t r = 1; r < L; ++r) p += q[r] * x[r];
    return p;
  }
  // The angular impulse in world coordinates (zero without angular rows).
  GPUSOLVE_HD math::Vector3<T> angular(const T* x) const {
    math::Vector3<T> m;
    for (std::size_t r = L; r < R; ++r) m += q[r - L] * x[r];
    return m;
  }
  // Q^T: the rows of a linear vector u and an angular one w (a relative
  // velocity and angular velocity, or a linear and an angular impulse).
  GPUSOLVE_HD void rows(const math::Vector3<T>& u, const math::Vector3<T>& w, T* out) const {
    for (std::size_t r = 0; r < L; ++r) out[r] = math::dot(q[r], u);
    for (std::size_t r = L; r < R; ++r) out[r] = math::dot(q[r - L], w);
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
  // The same with an angular impulse m as well, on a and, opposite, on b (a
  // model's angular rows). Apart from the two above so that a model without
  // angular rows computes exactly what it did.
  GPUSOLVE_HD BodyResponse(const ContactBodies<T>& k, const math::Vector3<T>& p, const math::Vector3<T>& m)
      : ia(k.ia), ib(k.ib), move_a(k.move_a), move_b(k.move_b), ra(k.ra), rb(k.rb) {
    dva = k.ma * p, dwa = k.Ia * (ra % p + m);
    dvb = -(k.mb * p), dwb = -(k.Ib * (rb % p + m));
  }
  template <class BV, class CV>
  GPUSOLVE_HD BodyResponse(const BV& b, const CV& c, std::size_t i, const math::Vector3<T>& p,
                           const math::Vector3<T>& m)
      : ia(c.a[i]), ib(c.b[i]), move_a(b.moving(ia)), move_b(b.moving(ib)), ra(math::load3<T>(c.ra, i)),
        rb(math::load3<T>(c.rb, i)) {
    dva = b.inv_mass[ia] * p, dwa = math::load9<T>(b.inv_inertia, ia) * (ra % p + m);
    dvb = -(b.inv_mass[ib] * p), dwb = -(math::load9<T>(b.inv_inertia, ib) * (rb % p + m));
  }
  // The change of the contact's relative velocity rows (Q^T of the relative
  // point velocity and angular velocity) that this response causes.
  template <class Model, class CV>
  GPUSOLVE_HD void rows(const Frame<T, Model, CV>& f, T* out) const {
    f.rows(point_velocity(dva, dwa, ra) - point_velocity(dvb, dwb, rb), dwa - dwb, out);
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

// The response to the impulse rows x of contact i in frame f, from the bodies
// `bodies` names: linear and angular where the model has angular rows.
template <class T, class Model, class Bodies, class BV, class CV>
GPUSOLVE_HD BodyResponse<T> response_of(const Bodies& bodies, const BV& b, const CV& c, std::size_t i,
                                        const Frame<T, Model, CV>& f, const T* x) {
  if constexpr (Model::rows > Model::linear_rows) {
    if constexpr (std::is_same_v<Bodies, LoadBodies>)
      return BodyResponse<T>(b, c, i, f.linear(x), f.angular(x));
    else
      return BodyResponse<T>(bodies, f.linear(x), f.angular(x));
  } else {
    return response_of<T>(bodies, b, c, i, f.linear(x));
  }
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
// with, per body, K p = m^-1 p + (I^-1 (r x p)) x r (= (m^-1 E - r× I^-1 r×) p)
// on a linear row and q . I^-1 q on an angular row about q, projected to the
// model's rows. Fixed bodies contribute nothing (zero inverse
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
// Coloured Gauss-Seidel updates a pair's points together too; the sequential
// reference (pgs.hpp) updates one point at a time, sees the others' changes
// and takes whole steps (`shared` false). A pair with one point, as every
// sphere pair, is unchanged.
template <class Model, class BV, class CV, class T>
struct InverseBlocks {
  BV b;
  CV c;
  const T* scale = nullptr;
  bool shared = true;  // a pair's k points take 1/k of a step each
  GPUSOLVE_HD void operator()(std::size_t i) const {
    constexpr std::size_t R = Model::rows, L = Model::linear_rows;
    const detail::Frame<T, Model, CV> f(c, i);
    const std::uint32_t ids[2] = {c.a[i], c.b[i]};
    const math::Vector3<T> rs[2] = {math::load3<T>(c.ra, i), math::load3<T>(c.rb, i)};
    T W[L][L] = {};      // the linear rows' block
    T A[R - L + 1] = {};  // the angular rows' diagonal (one spare entry: never empty)
    for (int s = 0; s < 2; ++s) {
      const std::uint32_t k = ids[s];
      const T im = b.inv_mass[k];
      const math::Matrix3x3<T> Iinv = math::load9<T>(b.inv_inertia, k);
      for (std::size_t col = 0; col < L; ++col) {
        const math::Vector3<T> Kq = im * f.q[col] + (Iinv * (rs[s] % f.q[col])) % rs[s];
        for (std::size_t row = 0; row < L; ++row) W[row][col] += math::dot(f.q[row], Kq);
      }
      for (std::size_t r = L; r < R; ++r) A[r - L] += math::dot(f.q[r - L], Iinv * f.q[r - L]);
    }
    const T s = (scale ? *scale : T(1)) / (shared ? T(pair_points(i)) : T(1));
    c.dinv(i, 0) = s / W[0][0];
    if constexpr (L == 3) c.dinv(i, 1) = c.dinv(i, 2) = s / (W[1][1] > W[2][2] ? W[1][1] : W[2][2]);
    if constexpr (R > L) {  // torsion about n, rolling about t and o by one scalar, as the friction rows
      c.dinv(i, 3) = s / A[0];
      c.dinv(i, 4) = c.dinv(i, 5) = s / (A[1] > A[2] ? A[1] : A[2]);
    }
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
// velocities, rhs = Q^T (va + wa x ra - vb - wb x rb) + (phi / dt, 0, 0), and
// on angular rows the relative angular velocity wa - wb about their axes.
// The normal row asks for a gap rate of at least -phi0/dt: a contact still
// open by phi0 may close within the step but no further (it is not pushed
// apart early). A penetration (phi0 < 0) is removed only by the fraction
// `correction` per step: removing it all at once turns a deep contact into a
// separation speed of |phi0|/dt, which throws bodies out of a pile. A contact
// that bounces (restitution: c.bounce > 0, set by detection for an impact
// within the step) asks for exactly that separation speed instead, with no
// position correction on top, which would add energy to the bounce. Where the
// contacts carry friction anchors, the friction rows likewise ask that
// `correction` of a sticking point's slip be undone (friction_anchors.hpp).
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
    f.rows(du, wa - wb, e);
    const T phi0 = c.phi0[i], bounce = c.bounce[i], approach = e[0];
    e[0] += (phi0 < T(0) ? correction * phi0 : phi0) * inv_dt;  // as without restitution, to the bit
    if (bounce > T(0)) e[0] = approach - bounce;
    if constexpr (Model::linear_rows == 3)
      if (c.anchored) {  // the sticking points' slip, corrected by the same share (friction_anchors.hpp)
        e[1] += correction * c.slip(i, 0) * inv_dt;
        e[2] += correction * c.slip(i, 1) * inv_dt;
      }
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
// iteration, |Q^T W Q (x' - x)|_inf, in m/s (on a model's angular rows, of the
// relative angular velocity, in rad/s); the solver's residual is its maximum
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
  // `record` false: not this update's residual, even where measuring.
  GPUSOLVE_HD void update(std::size_t i, const T (&e)[Model::rows], const Iterate& it = Iterate{},
                          const Bodies& bodies = Bodies{}, bool record = true) const {
    constexpr std::size_t R = Model::rows;
    const detail::Frame<T, Model, CV> f(c, i);
    T x0[R], y[R], x[R], dx[R];
    it.start(c, i, x0, y);
    for (std::size_t r = 0; r < R; ++r) x[r] = y[r] - omega * (c.dinv(i, r) * e[r]);
    Model::project(x, limits_of<Model, T>(c, i));
    for (std::size_t r = 0; r < R; ++r) dx[r] = x[r] - y[r];
    const detail::BodyResponse<T> d = detail::response_of<T>(bodies, b, c, i, f, dx);
    d.send(sink, i);
    it.store(c, i, e, x0, x);
    if (measure && record) {
      T du[R];
      d.rows(f, du);
      T m = 0;
      bool finite = true;
      for (std::size_t r = 0; r < R; ++r) {
        const T e = std::fabs(du[r]);
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
    detail::response_of<T>(detail::LoadBodies{}, b, c, i, f, x).send(sink, i);
  }
};

}  // namespace gpusolve::rbd
