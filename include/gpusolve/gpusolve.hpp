// Umbrella header: the containers, the launch layer and the math module.
// The rigid-body solver has its own umbrella, gpusolve/rbd.hpp.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/containers.hpp"
#include "gpusolve/math.hpp"
