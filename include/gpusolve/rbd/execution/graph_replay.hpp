// GraphReplay: runs a run of kernel launches as one CUDA graph, so that the
// device pays about a microsecond per kernel instead of a launch each.
#pragma once

#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

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
// run(key, work, stream) keeps the graph instead: while `key` (trivially
// copyable) has the bytes it had at the last capture, the graph is launched
// again without capturing; the caller's key must determine every argument of
// the launches work would queue (sizes, pointers, parameters), and its
// padding, its members' own included, must be zeroed or absent (DetectionKey),
// since the padding is compared too.
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

  template <class Key, class Work>
  void run(const Key& key, Work&& work, stream_t stream) {
    static_assert(std::is_trivially_copyable_v<Key>, "GraphReplay: a key is compared by its bytes");
    const auto* bytes = reinterpret_cast<const unsigned char*>(&key);
    if constexpr (std::is_same_v<Device, device::gpu>) {
#if GPUSOLVE_HAS_CUDART
      if (exec_ && key_.size() == sizeof(Key) && std::memcmp(key_.data(), bytes, sizeof(Key)) == 0) {
        GPUSOLVE_CUDA_CHECK(cudaGraphLaunch(exec_, stream));
        return;
      }
#endif
    }
    key_.clear();  // a capture that fails leaves no key
    run(std::forward<Work>(work), stream);
    key_.assign(bytes, bytes + sizeof(Key));
  }

  // Drops the kept graph's key, so that the next run(key, ...) captures anew:
  // for a caller whose launches outside the graph reallocated what it points to.
  void forget() { key_.clear(); }

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
      key_.clear();  // this graph is kept only by the run(key, ...) that captured it
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
  std::vector<unsigned char> key_;  // of the graph in exec_, when it may be kept
};

}  // namespace gpusolve::rbd::detail
