// Mass properties of a part by its kind and of a compound of parts: volume,
// and the inertia tensor about the centre of mass in the body frame for a
// given mass (each kind's own solid is in its header, sphere_shape.hpp, ...).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "gpusolve/core/error.hpp"
#include "gpusolve/math/matrix_functions.hpp"
#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/rbd/bodies/parts.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

// A sphere, box or capsule by its kind and shape parameters (its
// ShapeTraits' solid); another kind has no mass of its own.
template <class T>
SolidProperties<T> solid_primitive(ShapeKind kind, const std::array<T, shape_param_rows>& p, T mass) {
  return visit_kind<SolidProperties<T>, part_kinds>(
      kind, [&](auto k) { return ShapeTraits<decltype(k)::value>::solid(p, mass); },
      []() -> SolidProperties<T> { throw InvalidArgumentError("gpusolve: only a sphere, box or capsule is solid alone"); });
}

// A compound of uniform density: the parts share the mass by volume (where
// parts overlap, the overlap counts once per part). centre is the centre of
// mass in the compound's frame; inertia (row-major) is about it, the sum of
// each part's rotated tensor and its parallel-axis term m (|d|^2 E - d d^T).
template <class T>
struct CompoundProperties {
  T volume;
  std::array<T, 3> centre;
  std::array<T, 9> inertia;
};

template <class T>
CompoundProperties<T> solid_compound(const std::vector<Part<T>>& parts, T mass) {
  double volume = 0, centre[3] = {};
  for (const Part<T>& part : parts) {
    const double v = solid_primitive(part.shape, part.shape_param, T(1)).volume;
    volume += v;
    for (int r = 0; r < 3; ++r) centre[r] += v * part.pos[r];
  }
  for (double& c : centre) c /= volume;
  math::Matrix3x3<double> I;
  for (const Part<T>& part : parts) {
    const auto solid = solid_primitive(part.shape, part.shape_param, T(1));
    const double m = double(mass) * solid.volume / volume;
    const math::Matrix3x3<double> R = math::to_rotation_matrix(
        math::Quaternion<double>(part.q[0], part.q[1], part.q[2], part.q[3]));
    const math::Matrix3x3<double> own(m * solid.inertia[0], 0, 0, 0, m * solid.inertia[1], 0, 0, 0,
                                      m * solid.inertia[2]);
    const double d[3] = {part.pos[0] - centre[0], part.pos[1] - centre[1], part.pos[2] - centre[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    math::Matrix3x3<double> shift;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) shift(r, c) = m * ((r == c ? dd : 0.0) - d[r] * d[c]);
    I = math::Matrix3x3<double>(I + math::rotate_tensor(R, own) + shift);
  }
  CompoundProperties<T> out{T(volume), {T(centre[0]), T(centre[1]), T(centre[2])}, {}};
  for (int k = 0; k < 9; ++k) out.inertia[k] = T(I[k]);
  return out;
}

}  // namespace gpusolve::rbd
