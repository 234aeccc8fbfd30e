// The fields of a body that derive from its position, orientation and shape
// (thesis UpdateBodyKernel): rotation matrix, world inverse inertia, bounds.
#pragma once

#include <cstddef>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"

namespace gpusolve::rbd {

// Everything that derives from position, orientation and shape (thesis
// UpdateBodyKernel): the rotation matrix, the world inverse inertia R I^-1 R^T,
// the bounding-sphere radius and its AABB; with track_motion, the motion
// average (|v| + |w| blended half and half with its previous value).
template <class View, class T>
struct UpdateBody {
  View b;
  std::size_t first;
  bool track_motion;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    const std::size_t i = first + k;
    const BodyOffsets<T> off(b);
    math::Matrix3x3Global<T> R(b.R, off.m9, i), Iinv(b.inv_inertia, off.m9, i);
    R = math::to_rotation_matrix(math::QuaternionGlobal<T>(b.q, off.q4, i));
    Iinv = math::rotate_tensor(R, math::Matrix3x3Global<T>(b.inv_inertia_body, off.m9, i));
    const T r = bounding_radius(i);
    b.radius[i] = r;
    for (std::size_t c = 0; c < 3; ++c) {
      b.aabb(i, c) = b.pos(i, c) - r;
      b.aabb(i, c + 3) = b.pos(i, c) + r;
    }
    if (track_motion) {
      const T speed = math::norm(math::Vector3Global<T>(b.v, off.v3, i)) +
                      math::norm(math::Vector3Global<T>(b.w, off.v3, i));
      b.motion[i] = (b.motion[i] + speed) / 2;
    }
  }
  GPUSOLVE_HD T bounding_radius(std::size_t i) const {
    return shape_bound<T>(b.shape[i], b.shape_param(i, 0), b.shape_param(i, 1), b.shape_param(i, 2));
  }
};

// The size penetration is measured against (shapes.hpp's shape_feature_size).
template <class View>
GPUSOLVE_HD auto feature_size(const View& b, std::size_t i) {
  using T = std::remove_cv_t<std::remove_reference_t<decltype(b.shape_param(i, 0))>>;
  return shape_feature_size<T>(b.shape[i], b.shape_param(i, 0), b.shape_param(i, 1), b.shape_param(i, 2));
}

// Recomputes the derived fields of bodies [first, last) without touching motion
// (after bodies were set from outside, e.g. by the BodyManager).
template <class Device, class View>
void update_derived(Device dev, const View& b, std::size_t first, std::size_t last,
                    stream_t stream = stream_t{}) {
  using T = std::remove_cv_t<std::remove_reference_t<decltype(b.pos(0, 0))>>;
  if (last > first) launch(dev, last - first, UpdateBody<View, T>{b, first, false}, stream);
}

}  // namespace gpusolve::rbd
