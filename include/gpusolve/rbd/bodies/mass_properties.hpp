// Mass properties of the solid primitives: volume, and the inertia tensor
// about the centre of mass in the body frame for a given mass.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "gpusolve/math/matrix_functions.hpp"
#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/rotation.hpp"
#include "gpusolve/rbd/bodies/parts.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

inline constexpr double pi = 3.14159265358979323846;

// The principal inertia (about the body axes) and volume of each solid.
template <class T>
struct SolidProperties {
  T volume;
  std::array<T, 3> inertia;  // for the given mass
};

template <class T>
SolidProperties<T> solid_sphere(T r, T mass) {
  const T I = T(2) / T(5) * mass * r * r;
  return {T(4 * pi / 3) * r * r * r, {I, I, I}};
}

// Half extents h: I_x = m (h_y^2 + h_z^2) / 3, and so on.
template <class T>
SolidProperties<T> solid_box(const std::array<T, 3>& h, T mass) {
  const T x = h[0] * h[0], y = h[1] * h[1], z = h[2] * h[2];
  return {8 * h[0] * h[1] * h[2], {mass * (y + z) / 3, mass * (x + z) / 3, mass * (x + y) / 3}};
}

// Radius r, core segment of half length L along x: a cylinder of length 2L
// and two hemispheres, the mass shared by volume; each hemisphere's centre of
// mass lies 3r/8 beyond the segment's end.
template <class T>
SolidProperties<T> solid_capsule(T r, T L, T mass) {
  const T H = 2 * L;
  const T cylinder = T(pi) * r * r * H, balls = T(4 * pi / 3) * r * r * r;
  const T mc = mass * cylinder / (cylinder + balls), ms = mass - mc;
  const T axial = mc * r * r / 2 + ms * T(2) / T(5) * r * r;
  const T across = mc * (r * r / 4 + H * H / 12) + ms * (T(2) / T(5) * r * r + H * H / 4 + T(3) / T(8) * H * r);
  return {cylinder + balls, {axial, across, across}};
}

// A sphere, box or capsule by its kind and shape parameters (shapes.hpp).
template <class T>
SolidProperties<T> solid_primitive(ShapeKind kind, const std::array<T, shape_param_rows>& p, T mass) {
  if (kind == box) return solid_box<T>({p[0], p[1], p[2]}, mass);
  if (kind == capsule) return solid_capsule(p[0], p[1], mass);
  return solid_sphere(p[0], mass);
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
