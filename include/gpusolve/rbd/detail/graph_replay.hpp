// GraphReplay: runs a run of kernel launches as one CUDA graph, so that the
// device pays about a microsecond per kernel instead of a launch each.
#pragma once

#include <type_traits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd::detail {

// run(work, stream): work(s) queues launches on stream s. On the GPU they are
// captured on a private stream (the legacy default stream cannot capture) into
// a graph, which is instantiated the first time and afterwards updated in place
// (cudaGraphExecUpdate: same kernels, new arguments, far cheaper than a new
// instantiation), then launched on `stream`. work must not wait for the device;
// it may allocate (relaxed capture: storage that grows is allocated at once,
// outside the graph). On the CPU backend work(stream) runs as it is.
template <class Device>
class GraphReplay {
 public:
  GraphReplay() = default;
  GraphReplay(const GraphReplay&) = delete;
  GraphReplay& operator=(const GraphReplay&) = delete;
  ~GraphReplay() {
#if GPUSOLVE_HAS_CUDART
    if (exec_) (void)cudaGraphExecDestroy(exec_);  // no throw from a destructor
    if (capture_) (void)cudaStreamDestroy(capture_);
#endif
  }

  template <class Work>
  void run(Work&& work, stream_t stream) {
    if constexpr (std::is_same_v<Device, device::gpu>) {
#if GPUSOLVE_HAS_CUDART
      if (!capture_) GPUSOLVE_CUDA_CHECK(cudaStreamCreateWithFlags(&capture_, cudaStreamNonBlocking));
      GPUSOLVE_CUDA_CHECK(cudaStreamBeginCapture(capture_, cudaStreamCaptureModeRelaxed));
      try {
        work(capture_);
      } catch (...) {
        cudaGraph_t broken = nullptr;
        (void)cudaStreamEndCapture(capture_, &broken);  // leaves the stream usable
        if (broken) (void)cudaGraphDestroy(broken);
        throw;
      }
      cudaGraph_t graph = nullptr;
      GPUSOLVE_CUDA_CHECK(cudaStreamEndCapture(capture_, &graph));
      cudaGraphExecUpdateResultInfo info{};
      if (!exec_ || cudaGraphExecUpdate(exec_, graph, &info) != cudaSuccess) {
        (void)cudaGetLastError();  // a failed update is expected when the kernels changed: instantiate anew
        if (exec_) GPUSOLVE_CUDA_CHECK(cudaGraphExecDestroy(exec_));
        exec_ = nullptr;
        const cudaError_t e = cudaGraphInstantiate(&exec_, graph, 0);
        (void)cudaGraphDestroy(graph);
        GPUSOLVE_CUDA_CHECK(e);
      } else {
        (void)cudaGraphDestroy(graph);
      }
      GPUSOLVE_CUDA_CHECK(cudaGraphLaunch(exec_, stream));
#else
      (void)work, (void)stream;
      throw UnsupportedError("gpusolve: CUDA graphs need the CUDA runtime");
#endif
    } else {
      work(stream);
    }
  }

 private:
#if GPUSOLVE_HAS_CUDART
  cudaStream_t capture_ = nullptr;
  cudaGraphExec_t exec_ = nullptr;
#endif
};

}  // namespace gpusolve::rbd::detail
