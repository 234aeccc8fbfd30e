// The Solver concept: what every contact solver of the library promises, and
// the method tags that name one for World.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "gpusolve/core/device.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

// A METHOD is a tag type (Jacobi<>, ColouredGaussSeidel, ...) with
//   template <class Device, class T, class Model> using solver = ...;
//   static constexpr const char* name;
// and its solver S = Method::solver<Device, T, Model> is a default-constructible
// class with
//   static constexpr double default_omega;  // relaxation when SolverSettings::omega is 0
//   SolverStats<T> solve(Bodies<Device, T>&, Contacts<Device, T, Model>&,
//                        const SolverSettings<T>&, stream_t stream, bool from_x);
// The contract of solve():
//  - reads the bodies' velocities (the step's external impulses already applied),
//    masses, inertias, and the contacts' geometry (a, b, n, t, o, ra, rb, phi0, mu);
//  - writes the constrained velocities into the bodies and each contact's impulse
//    into contacts.x, in the contact frame (rows: normal, t, o), inside the
//    model's admissible set (Model::project); contacts.dinv is its own scratch;
//  - from_x: start from the impulses in contacts.x (warm start, warm_start.hpp),
//    whose velocity change it applies first; else from zero impulses;
//  - stops when the LCP residual (solvers/contact_kernels.hpp, the same
//    definition for all methods) is below SolverSettings::tolerance, or at
//    max_iterations; detects divergence with ConvergenceMonitor and retries at a
//    smaller omega through solve_relaxed (relaxation.hpp), reporting all of it
//    in SolverStats and throwing DivergenceError where the settings ask;
//  - calls settings.validate() first (InvalidArgumentError naming the field);
//  - runs on device::cpu and device::gpu with the same __host__ __device__
//    kernel bodies, keeping its scratch storage between calls.
//  - a solver that also advances the bodies (substepping) declares
//      static constexpr bool integrates = true;
//    then solve() receives the velocities before the step's external forces and
//    applies them, solves and moves the bodies for the whole step itself.
//  - a solver that can leave its verdict for later (JacobiSolver under its
//    persistent kernel) also offers
//      bool solve_queued(bodies, contacts, settings, stream, from_x, slot, stats);
//      void verdict(slot, stats) const;
//    solve_queued() returns true when it did not wait: stats then holds the
//    contact count until verdict() fills in the rest, once the stream has
//    passed the solve (slot 0 or 1: two solves in flight).
//  - a solver that takes contacts whose count only the backend knows (their
//    views' size() read in kernels, the host sizing by bound()) offers
//      void hold_while(const std::uint32_t* hold);
//    and does nothing in a solve while *hold is not 0: World::advance_unattended
//    then queues steps without waiting (solves_unattended below).
// Adding a method is one header that defines its tag and solver, and its tests.

template <class Method, class Device, class T, class Model>
using solver_t = typename Method::template solver<Device, T, Model>;

// Whether S offers solve() with the signature above (a compile-time check of the concept).
template <class S, class Device, class T, class Model, class = void>
struct is_solver : std::false_type {};
template <class S, class Device, class T, class Model>
struct is_solver<S, Device, T, Model,
                 std::void_t<decltype(std::declval<S&>().solve(
                                 std::declval<Bodies<Device, T>&>(), std::declval<Contacts<Device, T, Model>&>(),
                                 std::declval<const SolverSettings<T>&>(), stream_t{}, bool{})),
                             decltype(S::default_omega)>>
    : std::is_same<decltype(std::declval<S&>().solve(std::declval<Bodies<Device, T>&>(),
                                                     std::declval<Contacts<Device, T, Model>&>(),
                                                     std::declval<const SolverSettings<T>&>(), stream_t{}, bool{})),
                   SolverStats<T>> {};

// Whether solver S moves the bodies itself (see above); false when it does not say.
template <class S, class = void>
struct integrates : std::false_type {};
template <class S>
struct integrates<S, std::void_t<decltype(S::integrates)>> : std::bool_constant<S::integrates> {};

// Whether solver S offers solve_queued() and verdict() (see above).
template <class S, class Device, class T, class Model, class = void>
struct queues_verdict : std::false_type {};
template <class S, class Device, class T, class Model>
struct queues_verdict<S, Device, T, Model,
                      std::void_t<decltype(std::declval<S&>().solve_queued(
                                      std::declval<Bodies<Device, T>&>(), std::declval<Contacts<Device, T, Model>&>(),
                                      std::declval<const SolverSettings<T>&>(), stream_t{}, bool{}, std::size_t{},
                                      std::declval<SolverStats<T>&>())),
                                  decltype(std::declval<const S&>().verdict(std::size_t{},
                                                                            std::declval<SolverStats<T>&>()))>>
    : std::true_type {};

// Whether S solves contacts whose count only the backend knows
// (Contacts::count_on_device) and skips a held step (hold_while(hold): *hold
// not 0), so that World::advance_unattended queues its steps without a wait.
template <class S, class = void>
struct solves_unattended : std::false_type {};
template <class S>
struct solves_unattended<S, std::void_t<decltype(std::declval<S&>().hold_while(static_cast<const std::uint32_t*>(nullptr)))>>
    : std::true_type {};

// Whether solver S runs distributed: set_exchange(BodyExchange<T>*) shares its
// bodies' sums and reductions over ranks (every method but the Atomic sums).
template <class S, class T, class = void>
struct solves_distributed : std::false_type {};
template <class S, class T>
struct solves_distributed<S, T, std::void_t<decltype(std::declval<S&>().set_exchange(static_cast<BodyExchange<T>*>(nullptr)))>>
    : std::true_type {};

// The relaxation a solve uses: the settings' omega, or the method's default when it is 0.
template <class S, class T>
T omega_of(const SolverSettings<T>& s) {
  return s.omega > T(0) ? s.omega : T(S::default_omega);
}

}  // namespace gpusolve::rbd
