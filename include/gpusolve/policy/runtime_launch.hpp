// measured_launch: gpusolve::launch that records its time under a performance policy.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/policy/runtime.hpp"
#include "gpusolve/policy/runtime_stopwatch.hpp"

namespace gpusolve::runtime {

// As launch(d, n, f, stream). When R's performance facet is on, the launch is
// timed (CUDA events on `stream` for the GPU: this waits for the kernel) and
// recorded under `label` in performance_log(); otherwise it is a plain launch.
template <class R, class D, class F>
void measured_launch(const char* label, D d, std::size_t n, F f, stream_t stream = stream_t{}) {
  if constexpr (R::performance) {
    Stopwatch watch(std::is_same_v<D, device::gpu>, stream);
    launch(d, n, f, stream);
    record_launch<R>(LaunchRecord{label, D::name, n, watch.seconds()});
  } else {
    (void)label;
    launch(d, n, f, stream);
  }
}

}  // namespace gpusolve::runtime
