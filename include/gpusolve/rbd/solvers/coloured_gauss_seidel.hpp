// ColouredGaussSeidel: projected Gauss-Seidel made parallel by contact colouring.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/contacts/contact_colouring.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/contact_solver_base.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/solvers/solver.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// One contact of the current colour, order[first + k]: its next velocity error
// and its projected update, applied to its bodies at once (no other contact of
// the colour touches them).
template <class Model, class BV, class CV, class T>
struct GaussSeidelContact {
  CalcNextPhi<Model, BV, CV, T> phi;
  ResolveCollisions<Model, BV, CV, DirectSink<BV, T>, T> resolve;
  const std::uint32_t* order;
  std::size_t first;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    const std::size_t i = order[first + k];
    T e[Model::rows];
    phi.error(i, e);
    resolve.update(i, e);
  }
};

// The velocity change of the impulses in c.x, colour by colour (warm start).
template <class Model, class BV, class CV, class T>
struct GaussSeidelApply {
  ApplyImpulses<Model, BV, CV, DirectSink<BV, T>, T> apply;
  const std::uint32_t* order;
  std::size_t first;
  GPUSOLVE_HD void operator()(std::size_t k) const { apply(order[first + k]); }
};

}  // namespace detail

// Projected (block) Gauss-Seidel over contacts, parallel within a colour: the
// contacts are coloured on the device every step (ContactColouring) so that no
// two of one colour share a moving body, and one iteration sweeps the colours in
// order, each contact seeing the velocities its predecessors in the sweep left.
// The GPU form of the sequential reference (pgs.hpp), as in PhysX's and Bullet's
// GPU PGS solvers (graph colouring: Tonge, Benevolenski and Voroshilov 2012 use
// it for their mass-splitting Jacobi; Harada 2011, "A parallel constraint solver
// for a rigid body simulation"). It converges in fewer iterations than Jacobi and
// needs no under-relaxation (omega 1 by default), at the price of one launch per
// colour per iteration. Deterministic on both backends. Same contract as every
// solver (solver.hpp).
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
    if (!this->prepare(c, s, stats)) return stats;
    const Device dev{};
    launch(dev, c.size(), InverseBlocks<Model, BV, CV, T>{b, c, nullptr, false}, stream);  // whole steps: a sweep
    const std::size_t nc = c.size();
    colouring_.build(b, c, stream);
    stats.colours = colouring_.colours();
    const std::uint32_t* order = colouring_.order();
    const detail::DirectSink<BV, T> sink{b};
    // Runs f(colour's first position) over each colour's contacts, colour by colour.
    auto sweep = [&](auto make) {
      for (std::size_t k = 0; k < colouring_.colours(); ++k)
        launch(dev, colouring_.offset(k + 1) - colouring_.offset(k), make(colouring_.offset(k)), stream);
    };

    auto attempt = [&](T omega, SolverStats<T>& st) {
      if (from_x && st.retries == 0) {
        sweep([&](std::size_t first) {
          return detail::GaussSeidelApply<Model, BV, CV, T>{{b, c, sink}, order, first};
        });
      } else {
        contacts.x.fill(T(0), stream);
      }
      ConvergenceMonitor<T> monitor(s, st);
      const VectorD2View<T> rhs{};  // GaussSeidelContact keeps each error in registers: no store
      const CalcNextPhi<Model, BV, CV, T> phi{b, c, rhs, T(1) / s.dt, s.correction};
      for (std::size_t it = 1;; ++it) {
        const bool measure = monitor.checks(it);
        const ResolveCollisions<Model, BV, CV, detail::DirectSink<BV, T>, T> resolve{
            b, c, rhs, sink, omega, measure, this->residual_.view()};
        sweep([&](std::size_t first) {
          return detail::GaussSeidelContact<Model, BV, CV, T>{phi, resolve, order, first};
        });
        if (measure && monitor.stop(it, this->residual(b, nc, stream))) break;
      }
    };
    solve_relaxed(s, omega_of<ColouredGaussSeidelSolver>(s), b, this->start_, stats, attempt, stream);
    return stats;
  }

  const ContactColouring<Device>& colouring() const { return colouring_; }

 private:
  ContactColouring<Device> colouring_;
};

// The method tag (solver.hpp).
struct ColouredGaussSeidel {
  template <class Device, class T, class Model>
  using solver = ColouredGaussSeidelSolver<Device, T, Model>;
  static constexpr const char* name = "gauss-seidel";
};

}  // namespace gpusolve::rbd
