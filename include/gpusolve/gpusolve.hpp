// Umbrella header: the whole library.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/container/vector_d2_offset.hpp"
