// Backend tags: where a container's memory lives and where a launch runs.
#pragma once

#include <type_traits>

namespace gpusolve::device {

// Host memory and loops on the CPU (OpenMP where enabled).
struct cpu {
  static constexpr const char* name = "cpu";
};

// CUDA device memory and CUDA kernels.
struct gpu {
  static constexpr const char* name = "gpu";
};

template <class D>
inline constexpr bool is_device_v = std::is_same_v<D, cpu> || std::is_same_v<D, gpu>;

}  // namespace gpusolve::device
