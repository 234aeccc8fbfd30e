// The Worlds that the optional prebuilt library (CMake target
// gpusolve::worlds, src/) compiles once. A program linked to it gets
// GPUSOLVE_PREBUILT_WORLDS defined (and GPUSOLVE_PREBUILT_GPU_WORLDS where
// the library was built with nvcc), and these declarations keep its own
// translation units from compiling those Worlds' steps and kernels again: a
// World<device::gpu> program then compiles with nvcc in the time it takes to
// read the headers, or with a plain C++ compiler (docs/build_time.md). Other
// Worlds (another method, model, precision) compile from the headers as ever.
#pragma once

#include "gpusolve/rbd/world.hpp"

#if defined(GPUSOLVE_PREBUILT_WORLDS)
namespace gpusolve::rbd {
extern template class World<device::cpu, float>;
extern template class World<device::cpu, float, ConeFriction, AcceleratedJacobi<Gather>, spheres_and_planes>;
#if defined(GPUSOLVE_PREBUILT_GPU_WORLDS)
extern template class World<device::gpu, float>;
extern template class World<device::gpu, float, ConeFriction, AcceleratedJacobi<Gather>, spheres_and_planes>;
#endif
}  // namespace gpusolve::rbd
#endif
