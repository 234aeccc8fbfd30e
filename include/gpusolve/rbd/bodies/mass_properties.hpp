// Mass properties of the solid primitives: volume, and the inertia tensor
// about the centre of mass in the body frame for a given mass.
#pragma once

#include <array>

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

}  // namespace gpusolve::rbd
