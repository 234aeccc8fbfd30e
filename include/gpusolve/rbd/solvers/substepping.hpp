// SubsteppingSolver: several substeps per time step, each a short solve
// followed by a position update, in the TGS / soft-step family.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// A contact's gap after its bodies moved for h at their velocities:
// phi += h n . (v_a + w_a x r_a - v_b - w_b x r_b), the relative velocity of
// the contact point, exact to first order for every shape.
template <class BV, class CV, class T>
struct AdvanceGap {
  BV b;
  CV c;
  T h;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const std::uint32_t ia = c.a[i], ib = c.b[i];
    const math::Vector3<T> va = math::load3<T>(b.v, ia) + math::load3<T>(b.w, ia) % math::load3<T>(c.ra, i);
    const math::Vector3<T> vb = math::load3<T>(b.v, ib) + math::load3<T>(b.w, ib) % math::load3<T>(c.rb, i);
    c.phi0[i] += h * math::dot(math::load3<T>(c.n, i), math::Vector3<T>(va - vb));
  }
};

}  // namespace detail

// Substepping (Macklin et al. 2019, "Small steps in physics simulation"; PhysX's
// TGS solver; Box2D v3's soft step, Catto 2024): the step of length dt is split
// into s.substeps substeps of h = dt / substeps; each applies gravity for h,
// solves the contacts with the inner method from the last substep's impulses
// (at most max_iterations / substeps iterations each), moves the bodies for h
// and advances every contact's gap by the motion of its bodies, so the next
// substep's solve sees where the bodies now are. Contacts stay those found at
// the start of the step. The penetration correction per substep is chosen so
// that s.correction of a penetration is still removed per step. This solver
// integrates the bodies itself (integrates = true): World applies no forces and
// does not move them. On exit contacts.x holds the last substep's impulses, and
// contacts.phi0 the gaps at the end of the step. Statistics: iterations summed
// over substeps, the residual history of the last, the worst status of any.
template <class Device, class T, class Model, class Inner = AcceleratedJacobi<Gather>>
class SubsteppingSolver {
 public:
  using InnerSolver = solver_t<Inner, Device, T, Model>;
  static constexpr double default_omega = InnerSolver::default_omega;
  static constexpr bool integrates = true;
  using BodyStore = Bodies<Device, T>;
  using ContactStore = Contacts<Device, T, Model>;

  SolverStats<T> solve(BodyStore& bodies, ContactStore& contacts, const SolverSettings<T>& s,
                       stream_t stream = stream_t{}, bool from_x = false) {
    s.validate();
    const std::size_t n = s.substeps;
    const T h = s.dt / T(n);
    SolverSettings<T> sub = s;
    sub.dt = h;
    sub.max_iterations = s.max_iterations / n > 0 ? s.max_iterations / n : 1;
    if (s.check_every > sub.max_iterations) sub.check_every = sub.max_iterations;  // 0 stays the inner method's own
    sub.correction = T(1) - std::pow(T(1) - s.correction, T(1) / T(n));
    const math::Vector3<T> g(s.gravity[0], s.gravity[1], s.gravity[2]);
    SolverStats<T> stats;
    stats.contacts = contacts.size();
    for (std::size_t k = 0; k < n; ++k) {
      apply_forces(bodies, h, g, stream);
      SolverStats<T> st = inner_.solve(bodies, contacts, sub, stream, from_x || k > 0);
      move(bodies, h, stream);
      if (contacts.size() > 0)
        launch(Device{}, contacts.size(),
               detail::AdvanceGap<typename BodyStore::View, typename ContactStore::View, T>{bodies.view(),
                                                                                           contacts.view(), h},
               stream);
      stats.iterations += st.iterations;
      stats.total_iterations += st.total_iterations;
      stats.retries += st.retries;
      stats.omega = st.omega;
      stats.reduction_passes = st.reduction_passes;
      stats.colours = st.colours;
      stats.residuals = std::move(st.residuals);
      stats.checked_at = std::move(st.checked_at);
      if (int(st.status) > int(stats.status)) stats.status = st.status;  // converged < max_iterations < diverged
    }
    return stats;
  }

  // A distributed solve (rbd/distributed/), where the inner method runs
  // distributed: its exchange; the substeps' forces, moves and gaps are each
  // body's and contact's own, the same on every rank that holds them.
  template <class S = InnerSolver, std::enable_if_t<solves_distributed<S, T>::value, int> = 0>
  void set_exchange(BodyExchange<T>* exchange) {
    inner_.set_exchange(exchange);
  }

 private:
  InnerSolver inner_;
};

// The method tag (solver.hpp).
template <class Inner = AcceleratedJacobi<Gather>>
struct Substepping {
  template <class Device, class T, class Model>
  using solver = SubsteppingSolver<Device, T, Model, Inner>;
  static constexpr const char* name = "substepping";
};

}  // namespace gpusolve::rbd
