// StepSettings: the time step itself: its length and the gravity it applies.
#pragma once

#include <cmath>

#include "gpusolve/rbd/settings/setting_error.hpp"

namespace gpusolve::rbd {

template <class T>
struct StepSettings {
  T dt = T(0.0025);                         // time step (s)
  T gravity[3] = {T(0), T(0), T(-9.81)};    // m/s^2

  // Throws InvalidArgumentError naming the first offending field.
  void validate() const {
    if (!(dt > 0) || !std::isfinite(dt)) detail::bad_setting("dt", "must be positive and finite");
    for (T g : gravity)
      if (!std::isfinite(g)) detail::bad_setting("gravity", "must be finite");
  }
};

}  // namespace gpusolve::rbd
