// Helpers shared by the GPU step tests (test_rbd_step_pipeline.cu,
// test_rbd_unattended.cu): a NaN written on the device, the bodies' state, the pile's settings.
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "../host/test_rbd_scenes.hpp"

namespace rbd_test {

// Writes a NaN into component 0 of body i's velocity, on the device.
template <class BV>
struct PoisonVelocity {
  BV b;
  std::size_t i;
  GPUSOLVE_HD void operator()(std::size_t) const { b.v(i, 0) = std::numeric_limits<float>::quiet_NaN(); }
};

inline std::vector<float> host_state(const BodySet<float>& set) {
  std::vector<float> out;
  for (std::size_t i = 0; i < set.size(); ++i)
    for (int c = 0; c < 3; ++c) out.push_back(set[i].pos[c]), out.push_back(set[i].v[c]), out.push_back(set[i].w[c]);
  return out;
}

inline SolverSettings<float> settings() {
  SolverSettings<float> s;
  s.friction = 0.5f;
  s.margin = 0;
  return s;
}

}  // namespace rbd_test
