// The residual check shared by every solver: the measured LCP residual and
// ConvergenceMonitor, the stopping and divergence rules fed with it.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/contacts/extent.hpp"
#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd {

namespace detail {

// The one reduction of a residual check, over max(contacts, bodies) indices:
// residual[i] for a contact i, +inf where body i's velocity is not finite (so a
// NaN velocity reads as divergence even on a body without contacts), else 0.
template <class BV, class T>
struct ResidualOrNotFinite {
  BV b;
  VectorD1View<T> residual;
  Extent contacts;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    if (i < b.size())
      for (std::size_t c = 0; c < 3; ++c)
        if (!(std::fabs(b.v(i, c)) <= std::numeric_limits<T>::max()) ||
            !(std::fabs(b.w(i, c)) <= std::numeric_limits<T>::max()))
          return std::numeric_limits<T>::infinity();
    return i < contacts.size() ? residual[i] : T(0);
  }
  // The indices the terms span: max(contacts, bodies).
  GPUSOLVE_HD std::size_t width() const {
    const std::size_t nc = contacts.size();
    return nc > b.size() ? nc : b.size();
  }
};

}  // namespace detail

// The measured LCP residual of a solver: the largest residual of the contacts
// (ResolveCollisions with measure set), +inf when any body velocity is not
// finite; with an `exchange` (a distributed solve), the largest over the ranks.
// One reduction per check; its scratch is kept between checks.
template <class Device, class T>
class ResidualCheck {
 public:
  template <class BV>
  T operator()(const BV& b, VectorD1View<T> residual, std::size_t contacts, stream_t stream = stream_t{},
               BodyExchange<T>* exchange = nullptr) {
    const std::size_t n = contacts > b.size() ? contacts : b.size();
    if (out_.size_x() == 0) out_.resize(1);
    algorithms_.reduce_into(n, detail::ResidualOrNotFinite<BV, T>{b, residual, {contacts}}, T(0), detail::MaxOp{},
                            out_.data(), stream);
    if (exchange != nullptr) exchange->reduce(out_.data(), ExchangeOp::maximum, stream);
    return detail::read_back<Device>(out_.data(), 0, stream);
  }
  // Bytes of temporary storage held (GPU only; stays put once warm).
  std::size_t scratch_bytes() const { return algorithms_.scratch_bytes(); }

 private:
  detail::DeviceAlgorithms<Device> algorithms_;
  VectorD1<T, device_is<Device>> out_;  // the reduction's result slot
};

// The checks where SolveSettings::check_every is 0: every 10 iterations, so
// that a resting scene's solve stops at its first check below the tolerance;
// but after a check more than `far_from_tolerance` times the tolerance, only
// the last, since a solve that far off does not stop before its cap and its
// checks would buy nothing (docs/tuning/solve.md: settled, the 1 000-sphere
// pile's residual after 10 iterations was 6 to 22 times the tolerance, the
// standing scenes' at most 1.2 times).
inline constexpr std::size_t default_check_every = 10;
inline constexpr double far_from_tolerance = 4;

// The stopping and divergence rules of the residual checks, as plain data: the
// host applies them between runs of iterations (ConvergenceMonitor), and a
// persistent kernel applies the same rules itself, every thread reaching the
// same verdict from the same reduced residual (execution/persistent_loop.hpp), so
// its run of checks needs no host round trip.
template <class T>
struct ConvergenceRule {
  T tolerance, divergence_growth;
  std::size_t check_every, max_iterations, divergence_checks;
  T previous, smallest;
  std::size_t growing;
  std::size_t iterations;  // of the last check
  SolverStatus status;
  bool skips_when_far;  // the default schedule (check_every 0)
  bool far;             // the last check was far from the tolerance: the next is the last

  ConvergenceRule() = default;  // trivial, so that a kernel can keep one in shared memory
  explicit ConvergenceRule(const SolverSettings<T>& s)
      : tolerance(s.tolerance),
        divergence_growth(s.divergence_growth),
        check_every(s.check_every != 0 ? s.check_every : default_check_every),
        max_iterations(s.max_iterations),
        divergence_checks(s.divergence_checks),
        skips_when_far(s.check_every == 0) {
    restart();
  }

  // No check taken yet, as a solve's attempt begins.
  GPUSOLVE_HD void restart() {
    previous = smallest = std::numeric_limits<T>::infinity();
    growing = 0, iterations = 0;
    status = SolverStatus::converged;
    far = false;
  }

  // Whether iteration `it` (1-based) measures the residual: every check_every
  // iterations (after a far check, none but the last) and always the last one,
  // so the final residual is known.
  GPUSOLVE_HD bool checks(std::size_t it) const { return next_check(it) == it; }
  // The first iteration from `it` on that checks.
  GPUSOLVE_HD std::size_t next_check(std::size_t it) const {
    const std::size_t k = (it + check_every - 1) / check_every * check_every;
    return k < max_iterations && !far ? k : max_iterations;
  }
  // After stop() returned true: whether the attempt diverged.
  GPUSOLVE_HD bool diverged() const { return status == SolverStatus::diverged; }
  // How many checks a solve that runs to max_iterations makes.
  GPUSOLVE_HD std::size_t max_checks() const { return (max_iterations - 1) / check_every + 1; }

  // Takes the residual after iteration `it`; true when the solve must stop.
  // Diverged: the residual is not finite (NaN/inf in impulses or velocities), or it
  // grew at `divergence_checks` checks in a row to `divergence_growth` times its
  // smallest value so far. Converged: below the tolerance.
  GPUSOLVE_HD bool stop(std::size_t it, T residual) {
    iterations = it;
    if (!(residual <= std::numeric_limits<T>::max())) return finish(SolverStatus::diverged);
    if (residual < tolerance) return finish(SolverStatus::converged);
    growing = residual > previous ? growing + 1 : 0;
    previous = residual;
    smallest = residual < smallest ? residual : smallest;
    if (divergence_checks != 0 && growing >= divergence_checks && residual > divergence_growth * smallest)
      return finish(SolverStatus::diverged);
    if (it >= max_iterations) return finish(SolverStatus::max_iterations);
    far = skips_when_far && residual > T(far_from_tolerance) * tolerance;
    return false;
  }

 private:
  GPUSOLVE_HD bool finish(SolverStatus st) {
    status = st;
    return true;
  }
};

// ConvergenceRule applied on the host, recording each check in the solve's
// statistics (iterations, status and the residual history).
template <class T>
class ConvergenceMonitor {
 public:
  ConvergenceMonitor(const SolverSettings<T>& s, SolverStats<T>& stats) : rule_(s), stats_(stats) {}

  bool checks(std::size_t it) const { return rule_.checks(it); }
  std::size_t next_check(std::size_t it) const { return rule_.next_check(it); }

  // Records the residual after iteration `it`; returns true when the solve must stop.
  bool stop(std::size_t it, T residual) {
    stats_.residuals.push_back(residual);
    stats_.checked_at.push_back(it);
    const bool done = rule_.stop(it, residual);
    stats_.iterations = rule_.iterations;
    if (done) stats_.status = rule_.status;
    return done;
  }

 private:
  ConvergenceRule<T> rule_;
  SolverStats<T>& stats_;
};

// Records in `stats` the checks a ConvergenceRule made on the device: their
// residuals in order, the iterations they fell after (the rule taken through
// them again), and its verdict.
template <class T>
void record_checks(const ConvergenceRule<T>& verdict, std::vector<T> residuals, SolverStats<T>& stats) {
  stats.checked_at.clear();
  ConvergenceRule<T> again = verdict;
  again.restart();
  for (std::size_t k = 0, it = 0; k < residuals.size(); ++k) {
    stats.checked_at.push_back(it = again.next_check(it + 1));
    again.stop(it, residuals[k]);
  }
  stats.residuals = std::move(residuals);
  stats.iterations = verdict.iterations;
  stats.status = verdict.status;
}

}  // namespace gpusolve::rbd
