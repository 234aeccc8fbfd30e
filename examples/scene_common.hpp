// Pieces every scene shares: the edit record of a step hook, sphere mass, rotations, random numbers.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/quaternion_expr.hpp"
#include "gpusolve/math/vector3.hpp"

namespace scenes {

// Every scene is in metres, kilograms and seconds, z up, with gravity -9.81 m/s^2
// along z and spheres of radius 1 and density 1 (as pe's examples).
inline constexpr double gravity = 9.81;
inline constexpr double sphere_radius = 1.0;
inline constexpr double pi = 3.14159265358979323846;

template <class T>
T sphere_mass(T r) {
  return T(4.0 / 3.0 * pi) * r * r * r;  // density 1
}

// What a scene's step hook did to the host BodySet: the driver announces these
// to the BodyManager before the next synchronisation.
struct Changes {
  std::vector<std::size_t> added, removed;
  bool empty() const { return added.empty() && removed.empty(); }
};

// The unit quaternion (w, x, y, z) of `angle` radians about the unit `axis`,
// composed after `then` (the result rotates by `then` first).
template <class T>
std::array<T, 4> rotation(const std::array<T, 3>& axis, double angle,
                          const std::array<T, 4>& then = {1, 0, 0, 0}) {
  using gpusolve::math::Quaternion;
  using gpusolve::math::Vector3;
  const Quaternion<T> a = Quaternion<T>::from_axis_angle(Vector3<T>(axis[0], axis[1], axis[2]), T(angle));
  const Quaternion<T> q = a * Quaternion<T>(then[0], then[1], then[2], then[3]);
  return {q[0], q[1], q[2], q[3]};
}

// Seeded uniform numbers, so that a run is repeatable with --seed.
class Random {
 public:
  explicit Random(std::uint64_t seed) : gen_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }

 private:
  std::mt19937_64 gen_;
};

}  // namespace scenes
