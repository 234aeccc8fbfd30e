// SolidProperties: the volume and principal inertia of a solid of uniform density.
#pragma once

#include <array>

namespace gpusolve::rbd {

inline constexpr double pi = 3.14159265358979323846;

// The principal inertia (about the body axes, for the given mass) and volume.
template <class T>
struct SolidProperties {
  T volume;
  std::array<T, 3> inertia;
};

}  // namespace gpusolve::rbd
