// ProgramSolve: runs a solver written as programs (a start and an iteration,
// persistent_loop.hpp) as one persistent kernel or as launches, with the
// residual checks and the retries of a diverging attempt either way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/memory/cuda_host_allocator.hpp"
#include "gpusolve/memory/standard_allocator.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/execution/graph_replay.hpp"
#include "gpusolve/rbd/execution/launch_exec.hpp"
#include "gpusolve/rbd/execution/persistent_loop.hpp"
#include "gpusolve/rbd/execution/stream_marks.hpp"
#include "gpusolve/rbd/solvers/convergence.hpp"
#include "gpusolve/rbd/solvers/relaxation.hpp"
#include "gpusolve/rbd/settings/solver_settings.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"

namespace gpusolve::rbd::detail {

// Contact i's impulses set to zero: a retry starts cold.
template <class CV>
struct ZeroImpulses {
  CV c;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    for (std::size_t r = 0; r < c.x.size_y(); ++r) c.x(i, r) = 0;
  }
};

// The residual check's phase at the end of a run's last iteration: the
// largest of the terms (ResidualOrNotFinite, over its width()) into *out,
// read after the barrier that ends it.
GPUSOLVE_EXEC_CHECK_DISABLE
template <class E, class Terms, class T>
GPUSOLVE_HD void reduce_residual(const E& e, const Terms& terms, T* out) {
  e.reduce(terms.width(), terms, T(0), MaxOp{}, out);
  e.sync();
}

// The phases a retry inside a persistent kernel starts with, as solve_relaxed
// does on the host between attempts: the velocities the solve began with back
// (`save`, CopyVelocities), zero impulses.
GPUSOLVE_EXEC_CHECK_DISABLE
template <class E, class Save, class CV>
GPUSOLVE_HD void restart_cold(const E& e, Save back, const CV& c) {
  back.restore = true;
  e.each(back.b.size(), back);
  e.each(c.size(), ZeroImpulses<CV>{c});
  e.sync();
}

// The programs' shared state: the residual check's slot and reductions, the
// retry scale (*scale() multiplies the inverse blocks: a retry at a smaller
// omega scales them instead of rebuilding an iteration), the persistent
// kernel and what it leaves for the host, the graphs of launched runs.
// The iteration program must reduce its last iteration's residual into
// residual_out(), and the start program must build the inverse blocks with
// scale().
template <class Device, class T>
class ProgramSolve {
 public:
  // Whether a solve of `expected` contacts runs as one persistent kernel (never
  // a distributed one: its exchanges are the host's).
  bool persistent(std::size_t expected, const SolverSettings<T>& s) const {
    return exchange_ == nullptr && expected <= s.persistent_max_contacts && PersistentLoop<Device, T>::available();
  }

  // The ranks a solve shares its bodies with (nullptr: none). A distributed
  // solve runs as launches, without graphs, and every reduction and body sum
  // goes through the exchange.
  void set_exchange(BodyExchange<T>* exchange) { exchange_ = exchange; }
  BodyExchange<T>* exchange() const { return exchange_; }

  // Before a solve's programs are made: the residual's slot, the retry scale,
  // and, for graphs, the reductions' storage over `width` terms.
  template <class Terms>
  void prepare(const Terms& terms, std::size_t width, const SolverSettings<T>& s, stream_t stream) {
    if (residual_out_.size_x() == 0) residual_out_.resize(1);
    if (s.graphs) {  // a capture may not grow the reductions' buffers (the first node would keep the old one)
      algorithms_.reserve_reduce(width, terms, T(0), MaxOp{}, residual_out_.data());
      algorithms_.reserve_reduce(width, terms, T(0), PlusOp{}, residual_out_.data());
    }
    if (scale_.size_x() == 0) {
      scale_.resize(1);
      scale_.fill(T(1), stream);
    }
  }
  T* residual_out() { return residual_out_.data(); }
  const T* scale() const { return scale_.data(); }
  LaunchExec<Device, T> launched(stream_t stream) { return {stream, &algorithms_, exchange_}; }

  // The whole solve as one kernel: attempts of `start` (start(e, retry)), runs
  // of `iteration` between the checks, `between` after a check that goes on;
  // checks and retries run in it, and the host waits for its verdict at most
  // (not at all when `deferred`: then it returns true and verdict(slot, stats)
  // fills `stats` in once the stream has passed the solve). Nothing runs where
  // `hold` is set and *hold is not 0.
  template <class Start, class Iteration, class Between>
  bool run_persistent(const Start& start, const Iteration& iteration, const Between& between,
                      const SolverSettings<T>& s, T omega, std::size_t width, std::size_t slot, bool deferred,
                      const std::uint32_t* hold, stream_t stream, SolverStats<T>& stats) {
    if (!scale_is_one_) scale_.fill(T(1), stream);
    scale_is_one_ = true;  // the kernel leaves it 1
    const ConvergenceRule<T> rule(s);
    if (records_.size() == 0) records_ = HostBuffer<Record>(2);
    if (histories_[slot].size() < rule.max_checks()) histories_[slot] = HostBuffer<T>(rule.max_checks());
    omegas_[slot] = omega, retry_factors_[slot] = s.retry_omega_factor;
    persistent_.set_clusters(s.persistent_clusters);
    persistent_.run_checked(start, iteration, between, rule, RetryRule<T>{s.retry_omega_factor, s.max_retries, scale_.data()},
                            residual_out_.data(), records_.data() + slot, histories_[slot].data(), width, stream, hold);
    if (deferred) return true;
    done_.mark(0, stream);
    done_.wait(0);
    verdict(slot, stats);
    report_divergence(s, stats);
    return false;
  }

  // Fills in the verdict of the persistent solve queued in `slot`: status,
  // iterations, residual history, retries, omega. The stream must have passed it.
  void verdict(std::size_t slot, SolverStats<T>& stats) const {
    const Record r = records_.data()[slot];
    const std::vector<T> checks(histories_[slot].data(), histories_[slot].data() + r.checks);
    record_checks(r.rule, checks, stats);
    stats.retries = r.retries, stats.total_iterations = r.total_iterations;
    stats.omega = omegas_[slot];
    for (std::size_t k = 0; k < r.retries; ++k) stats.omega *= retry_factors_[slot];  // as solve_relaxed
  }

  // The solve as launches: per attempt (solve_relaxed) its start
  // (make_start(first_attempt), a program), then runs of iterations up to each
  // residual check (replayed as a graph with s.graphs), the check read on the
  // host, after_run(e) after a run that goes on. A retry starts from zero
  // impulses (`x`) at the blocks' scale attempt omega / omega.
  template <class BV, class Impulses, class MakeStart, class Iteration, class AfterRun>
  void run_launched(const BV& b, Impulses& x, VelocitySnapshot<Device, T>& snapshot, const SolverSettings<T>& s,
                    T omega, const MakeStart& make_start, const Iteration& iteration, const AfterRun& after_run,
                    stream_t stream, SolverStats<T>& stats) {
    auto attempt = [&](T attempt_omega, SolverStats<T>& st) {
      const bool first_attempt = st.retries == 0;
      if (!first_attempt) x.fill(T(0), stream);
      scale_.fill(attempt_omega / omega, stream);
      scale_is_one_ = attempt_omega == omega;
      const auto start = make_start(first_attempt);
      // Iterations `first` ... `last`, the last one measuring the residual.
      auto iterations = [&](std::size_t first, std::size_t last, stream_t q) {
        const LaunchExec<Device, T> e{q, &algorithms_, exchange_};
        for (std::size_t it = first; it <= last; ++it) iteration(e, it - first + 1, it == last);
      };
      ConvergenceMonitor<T> monitor(s, st);
      for (std::size_t first = 1;;) {
        const std::size_t last = monitor.next_check(first);
        if (first == 1) start(launched(stream));  // a graph's kernels stay the same from run to run without the start's
        if (s.graphs && exchange_ == nullptr)
          graph_.run([&](stream_t q) { iterations(first, last, q); }, stream);
        else
          iterations(first, last, stream);
        if (monitor.stop(last, read_back<Device>(residual_out_.data(), 0, stream))) break;
        after_run(launched(stream));
        first = last + 1;
      }
    };
    solve_relaxed(s, omega, b, snapshot, stats, attempt, stream, true);
  }

 private:
  // What the persistent kernel leaves for the host (pinned on the GPU).
  template <class E>
  using HostBuffer = memory::Buffer<
      E, std::conditional_t<std::is_same_v<Device, device::gpu>, memory::CUDAHostAllocator, memory::StandardAllocator>>;
  using Record = CheckedRun<ConvergenceRule<T>>;

  DeviceAlgorithms<Device> algorithms_;      // the programs' reductions
  VectorD1<T, device_is<Device>> residual_out_;  // the residual check's maximum
  GraphReplay<Device> graph_;                // SolverSettings::graphs
  PersistentLoop<Device, T> persistent_;     // SolverSettings::persistent_max_contacts
  HostBuffer<Record> records_;               // per slot (solve_queued)
  HostBuffer<T> histories_[2];               // per slot: the residual of each check of the last attempt
  T omegas_[2] = {}, retry_factors_[2] = {};
  VectorD1<T, device_is<Device>> scale_;  // the inverse blocks' factor: retry_omega_factor^retries
  bool scale_is_one_ = true;               // *scale_ between solves, as the host last queued it
  StreamMarks<Device, 1> done_;
  BodyExchange<T>* exchange_ = nullptr;  // set_exchange
};

}  // namespace gpusolve::rbd::detail
