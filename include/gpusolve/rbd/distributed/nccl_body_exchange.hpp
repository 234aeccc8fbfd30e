// NcclBodyExchange: the exchange of a distributed world on the GPU backend
// between GPUs, with NCCL: the shared bodies' values go from GPU to GPU as
// grouped point-to-point sends, the reductions are NCCL all-reduces in place,
// all queued on the solve's stream, so no iteration waits for the host. Each
// rank needs a GPU of its own: NCCL refuses two ranks on one GPU (use
// MpiBodyExchange there). Needs NCCL (nccl.h, libnccl; GPUSOLVE_WITH_NCCL).
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

#include <cuda_runtime_api.h>
#include <mpi.h>
#include <nccl.h>

#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/distributed/body_sum_exchange.hpp"
#include "gpusolve/rbd/distributed/rank_agreement.hpp"

namespace gpusolve::rbd {

// An NCCL call failed: names the call and NCCL's reason.
class NcclError : public Error {
 public:
  NcclError(int code, const std::string& what) : Error(what), code_(code) {}
  int code() const noexcept { return code_; }

 private:
  int code_;
};

namespace detail {
inline void nccl_check(ncclResult_t r, const char* call) {
  if (r != ncclSuccess)
    throw NcclError(int(r), std::string("gpusolve: ") + call + " failed: " + ncclGetErrorString(r));
}

template <class T>
ncclDataType_t nccl_type() {
  return sizeof(T) == 4 ? ncclFloat32 : ncclFloat64;
}

inline ncclRedOp_t nccl_op(ExchangeOp op) {
  return op == ExchangeOp::maximum ? ncclMax : op == ExchangeOp::minimum ? ncclMin : ncclSum;
}
}  // namespace detail

// BodySumExchange's transport between GPUs. Made collectively over `comm`
// (every rank's current GPU its own: use_rank_gpu on a node of a GPU per
// rank); where two ranks share a GPU (UnsupportedError) or NCCL fails
// (RankFailedError), every rank throws. Its exchanges are queued on the
// stream, where no RankAlarm reaches them: a rank that fails inside a step
// leaves the others waiting in NCCL (ncclCommAbort is not wired).
template <class T>
class NcclTransport {
 public:
  NcclTransport(MPI_Comm comm, RankAlarm*) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &ranks_);
    const RankAgreement agree(comm);
    cudaDeviceProp gpu{};
    agree.run([&] {
      int device = 0;
      GPUSOLVE_CUDA_CHECK(cudaGetDevice(&device));
      GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&gpu, device));
    });
    std::vector<char> gpus(16 * std::size_t(ranks_));
    MPI_Allgather(gpu.uuid.bytes, 16, MPI_BYTE, gpus.data(), 16, MPI_BYTE, comm);
    require_own_gpus(gpus);  // every rank holds the same list: every rank decides alike
    ncclUniqueId id;
    agree.run([&] {
      if (rank == 0) detail::nccl_check(ncclGetUniqueId(&id), "ncclGetUniqueId");
    });
    MPI_Bcast(&id, int(sizeof id), MPI_BYTE, 0, comm);
    try {
      agree.run([&] { detail::nccl_check(ncclCommInitRank(&comm_, ranks_, id, rank), "ncclCommInitRank"); });
    } catch (...) {
      if (comm_ != nullptr) ncclCommDestroy(comm_);  // this rank's part of a communicator another rank lacks
      throw;
    }
  }
  NcclTransport(const NcclTransport&) = delete;
  NcclTransport& operator=(const NcclTransport&) = delete;
  ~NcclTransport() {
    if (comm_ != nullptr) ncclCommDestroy(comm_);
  }

  int ranks() const { return ranks_; }

  void send(const T* out, const std::vector<std::size_t>& out_counts, const std::vector<std::size_t>& out_offsets,
            T* in, const std::vector<std::size_t>& in_counts, const std::vector<std::size_t>& in_offsets,
            stream_t stream) {
    detail::nccl_check(ncclGroupStart(), "ncclGroupStart");
    for (int r = 0; r < ranks_; ++r) {
      if (out_counts[r] != 0)
        detail::nccl_check(ncclSend(out + out_offsets[r], out_counts[r], detail::nccl_type<T>(), r, comm_, stream),
                           "ncclSend");
      if (in_counts[r] != 0)
        detail::nccl_check(ncclRecv(in + in_offsets[r], in_counts[r], detail::nccl_type<T>(), r, comm_, stream),
                           "ncclRecv");
    }
    detail::nccl_check(ncclGroupEnd(), "ncclGroupEnd");
  }

  void reduce(T* value, ExchangeOp op, stream_t stream) {
    detail::nccl_check(ncclAllReduce(value, value, 1, detail::nccl_type<T>(), detail::nccl_op(op), comm_, stream),
                       "ncclAllReduce");
  }

 private:
  // Every rank on a GPU of its own (`gpus`: every rank's UUID, 16 bytes
  // each), or an UnsupportedError naming two ranks that share one, before
  // NCCL is asked.
  void require_own_gpus(const std::vector<char>& gpus) const {
    for (int r = 0; r < ranks_; ++r)
      for (int s = r + 1; s < ranks_; ++s)
        if (std::memcmp(&gpus[16 * std::size_t(r)], &gpus[16 * std::size_t(s)], 16) == 0)
          throw UnsupportedError("gpusolve: NcclBodyExchange: ranks " + std::to_string(r) + " and " +
                                 std::to_string(s) + " share a GPU, which NCCL refuses; share it through "
                                 "RankTransport::mpi_host");
  }

  int ranks_ = 1;
  ncclComm_t comm_ = nullptr;
};

template <class T>
using NcclBodyExchange = BodySumExchange<device::gpu, T, NcclTransport<T>>;

}  // namespace gpusolve::rbd
