// SolverSettings: every setting of a World, as four groups by concern, each
// validated on its own: the step, the contacts, the solve, the execution.
#pragma once

#include "gpusolve/rbd/settings/contact_settings.hpp"
#include "gpusolve/rbd/settings/execution_settings.hpp"
#include "gpusolve/rbd/settings/solve_settings.hpp"
#include "gpusolve/rbd/settings/step_settings.hpp"

namespace gpusolve::rbd {

// One aggregate of the four groups: `s.dt`, `s.margin`, `s.max_iterations` and
// `s.graphs` read as before, a stage that needs one concern takes its group
// (a SolverSettings converts to each), and a user may brace-initialise it group
// by group: SolverSettings<float>{{dt, {0, 0, -9.81f}}, {margin}, {omega}, {}}.
template <class T>
struct SolverSettings : StepSettings<T>, ContactSettings<T>, SolveSettings<T>, ExecutionSettings {
  const StepSettings<T>& step() const { return *this; }
  const ContactSettings<T>& contacts() const { return *this; }
  const SolveSettings<T>& solve() const { return *this; }
  const ExecutionSettings& execution() const { return *this; }

  // Throws InvalidArgumentError naming the first offending field, group by group.
  void validate() const {
    step().validate();
    contacts().validate();
    solve().validate();
    execution().validate();
  }
};

}  // namespace gpusolve::rbd
