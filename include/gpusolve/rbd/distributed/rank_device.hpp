// RankDevice: which GPU each rank of a distributed world uses. The ranks that
// share a node take its GPUs in turn (local rank modulo the GPUs the node
// shows), so eight ranks on a node of eight GPUs use one each, and two ranks
// on a node of one GPU share it.
#pragma once

#include <mpi.h>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/distributed/rank_agreement.hpp"

namespace gpusolve::rbd {

// A rank's place among the ranks of its node (MPI_COMM_TYPE_SHARED).
struct NodePlace {
  int local_rank = 0, local_ranks = 1;
};

// Collective over `comm`.
inline NodePlace node_place(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  NodePlace p;
  MPI_Comm_rank(node, &p.local_rank);
  MPI_Comm_size(node, &p.local_ranks);
  MPI_Comm_free(&node);
  return p;
}

// The GPU of the rank at `p` on a node that shows `devices` (at least one).
inline int rank_gpu(const NodePlace& p, int devices) { return p.local_rank % devices; }

#if GPUSOLVE_HAS_CUDART
// Makes this rank's GPU (rank_gpu) the current device and returns it; every
// rank of `comm` calls it before it makes its DistributedWorld. A rank that
// finds no usable GPU makes every rank throw (RankAgreement).
inline int use_rank_gpu(MPI_Comm comm) {
  const NodePlace p = node_place(comm);
  int device = 0;
  RankAgreement(comm).run([&] {
    int devices = 0;
    GPUSOLVE_CUDA_CHECK(cudaGetDeviceCount(&devices));
    device = rank_gpu(p, devices);
    GPUSOLVE_CUDA_CHECK(cudaSetDevice(device));
  });
  return device;
}
#endif

}  // namespace gpusolve::rbd
