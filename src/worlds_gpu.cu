// The prebuilt library's Worlds on the GPU backend (prebuilt_worlds.hpp).
#include "gpusolve/rbd/prebuilt_worlds.hpp"

namespace gpusolve::rbd {
template class World<device::gpu, float>;
template class World<device::gpu, float, ConeFriction, AcceleratedJacobi<Gather>, spheres_and_planes>;
}  // namespace gpusolve::rbd
