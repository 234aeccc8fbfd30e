// snapshot: the Frame of a host BodySet (what the frame writers draw), removed bodies left out.
#pragma once

#include <cstddef>

#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/io/frame.hpp"

namespace gpusolve::rbd::io {

template <class T>
Frame snapshot(const BodySet<T>& bodies, std::size_t step, double time) {
  Frame f;
  f.step = step;
  f.time = time;
  for (const auto& b : bodies.records()) {
    if (b.status == removed) continue;
    const Frame::Vec3 p{double(b.pos[0]), double(b.pos[1]), double(b.pos[2])};
    const auto& s = b.shape_param;
    switch (b.shape) {
      case sphere:
        f.add_sphere(p, s[0], {double(b.v[0]), double(b.v[1]), double(b.v[2])});
        break;
      case box: {
        const auto R = math::to_rotation_matrix(math::Quaternion<T>(b.q[0], b.q[1], b.q[2], b.q[3]));
        Frame::Box x{p, {double(s[0]), double(s[1]), double(s[2])}, {}, b.status == active};
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) x.R[3 * r + c] = R(r, c);
        f.boxes.push_back(x);
        break;
      }
      case capsule: {
        const auto R = math::to_rotation_matrix(math::Quaternion<T>(b.q[0], b.q[1], b.q[2], b.q[3]));
        f.capsules.push_back({p, {double(R(0, 0)), double(R(1, 0)), double(R(2, 0))}, double(s[0]), double(s[1])});
        break;
      }
      case plane:
        f.planes.push_back({{double(s[0]), double(s[1]), double(s[2])}, double(s[3])});
        break;
    }
  }
  return f;
}

}  // namespace gpusolve::rbd::io
