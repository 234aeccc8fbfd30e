// RunRecord: the per-step statistics of a scene run (stats.csv) and their totals (summary.json).
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "gpusolve/rbd/io/csv_writer.hpp"
#include "gpusolve/rbd/io/json_writer.hpp"
#include "gpusolve/rbd/statistics/solver_stats.hpp"
#include "scene_options.hpp"

namespace scenes {

// stats.csv columns. status: 0 converged, 1 stopped at max_iterations, 2 diverged
// (after all retries); iterations: all attempts of the step; retries: restarts at
// a lower omega after a diverging attempt, omega: the one the step ended with.
// max_penetration is relative to the smaller radius of the pair; energies in J
// (potential zero at z = 0); t_* are wall seconds of the phases, t_step of the
// whole step including the scene's edits and the host/device synchronisation.
inline const std::vector<std::string>& stats_columns() {
  static const std::vector<std::string> c{
      "step", "time", "bodies", "contacts", "iterations", "residual", "status", "retries", "omega",
      "max_penetration",
      "kinetic", "potential", "energy", "t_detection", "t_solve", "t_integration", "t_step"};
  return c;
}

class RunRecord {
 public:
  RunRecord(const std::string& dir, long csv_every)
      : csv_(dir + "/stats.csv", stats_columns()), every_(csv_every) {}

  template <class T>
  void add(long step, double time, std::size_t bodies, const gpusolve::rbd::StepStats<T>& s, double t_step) {
    const auto& v = s.solver;
    if (step % every_ == 0)
      csv_.row({double(step), time, double(bodies), double(v.contacts), double(v.total_iterations),
                double(v.residual()), double(static_cast<int>(v.status)), double(v.retries), double(v.omega),
                double(s.max_penetration), double(s.kinetic_energy),
                double(s.potential_energy), double(s.energy()), s.time_detection, s.time_solve,
                s.time_integration, t_step});
    ++steps_;
    // NaN must not hide in a max: a non-finite penetration is the run's maximum.
    const double pen = s.max_penetration;
    max_pen_ = std::isfinite(pen) ? std::max(max_pen_, pen) : pen;
    if (std::isfinite(max_pen_) && pen == max_pen_) max_pen_step_ = step;
    sum_it_ += v.total_iterations;
    max_it_ = std::max<std::size_t>(max_it_, v.total_iterations);
    retried_ += v.retries > 0;
    max_contacts_ = std::max(max_contacts_, v.contacts);
    last_contacts_ = v.contacts;
    diverged_ += v.status == gpusolve::rbd::SolverStatus::diverged;
    unconverged_ += v.status == gpusolve::rbd::SolverStatus::max_iterations;
    sum_time_ += t_step;
    sum_detection_ += s.time_detection, sum_solve_ += s.time_solve, sum_integration_ += s.time_integration;
    if (steps_ == 1) first_energy_ = s.energy();
    last_energy_ = s.energy();
    last_bodies_ = bodies;
  }

  long divergence_events() const { return diverged_; }
  double max_penetration() const { return max_pen_; }

  // summary.json: what ran (scene, backend, device, parameters) and the totals.
  void write_summary(const std::string& path, const Options& o, const std::string& backend,
                     const std::string& device, const std::string& model, const std::string& solver,
                     const std::string& accumulation, double wall_seconds) const {
    std::ofstream out(path);
    if (!out) throw gpusolve::InvalidArgumentError("cannot write " + path);
    gpusolve::rbd::io::JsonWriter j(out);
    const double n = std::max(1L, steps_);
    j.begin_object()
        .field("scene", o.scene)
        .field("backend", backend)
        .field("device", device)
        .begin_object("parameters")
        .field("steps", *o.steps)
        .field("scale", *o.scale)
        .field("dt", *o.dt)
        .field("omega", o.omega)
        .field("margin", o.margin)
        .field("tolerance", *o.tolerance)
        .field("max_iterations", *o.max_iterations)
        .field("max_retries", o.max_retries)
        .field("warm_start", o.warm_start)
        .field("check_every", *o.check_every)
        .field("friction", *o.friction)
        .field("model", model)
        .field("solver", solver)
        .field("accumulation", accumulation)
        .field("seed", o.seed)
        .end_object()
        .begin_object("totals")
        .field("steps", steps_)
        .field("bodies", last_bodies_)
        .field("final_contacts", last_contacts_)
        .field("max_contacts", max_contacts_)
        .field("max_penetration", max_pen_)
        .field("max_penetration_step", max_pen_step_)
        .field("mean_iterations", sum_it_ / n)
        .field("max_iterations", max_it_)
        .field("unconverged_steps", unconverged_)
        .field("retried_steps", retried_)
        .field("divergence_events", diverged_)
        .field("first_energy", first_energy_)
        .field("last_energy", last_energy_)
        .field("mean_step_seconds", sum_time_ / n)
        .field("mean_detection_seconds", sum_detection_ / n)
        .field("mean_solve_seconds", sum_solve_ / n)
        .field("mean_integration_seconds", sum_integration_ / n)
        .field("wall_seconds", wall_seconds)
        .end_object()
        .end_object();
  }

 private:
  gpusolve::rbd::io::CsvWriter csv_;
  long every_;
  long steps_ = 0, diverged_ = 0, unconverged_ = 0, retried_ = 0, max_pen_step_ = -1;
  double max_pen_ = 0, sum_it_ = 0, sum_time_ = 0, sum_detection_ = 0, sum_solve_ = 0, sum_integration_ = 0;
  double first_energy_ = 0, last_energy_ = 0;
  std::size_t max_it_ = 0, max_contacts_ = 0, last_contacts_ = 0, last_bodies_ = 0;
};

}  // namespace scenes
