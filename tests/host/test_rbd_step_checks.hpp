// Checks shared by the step tests on the CPU backend (test_rbd_step_pipeline.cpp,
// test_rbd_unattended.cpp): the pile's settings, the bodies' state, the statistics.
#pragma once

#include <cstddef>
#include <vector>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"

namespace rbd_test {

inline SolverSettings<double> pile_settings() {
  SolverSettings<double> s;
  s.friction = 0.4;
  s.margin = 0;  // so that contacts overlap and the penetration figure is not zero
  return s;
}

// Positions and velocities of every body, bit for bit.
template <class W>
std::vector<double> state(W& w) {
  auto& b = w.bodies();
  std::vector<double> out;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) out.push_back(b.pos(i, c)), out.push_back(b.v(i, c)), out.push_back(b.w(i, c));
  return out;
}

inline void same_stats(const StepStats<double>& a, const StepStats<double>& b) {
  CHECK(a.solver.contacts == b.solver.contacts);
  CHECK(a.solver.iterations == b.solver.iterations);
  CHECK(a.solver.residual() == b.solver.residual());
  CHECK(a.max_penetration == b.max_penetration);
  CHECK(a.kinetic_energy == b.kinetic_energy);
  CHECK(a.potential_energy == b.potential_energy);
}

}  // namespace rbd_test
