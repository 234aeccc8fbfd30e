// ExecutionSettings: how a step runs on the GPU (CUDA graphs, the persistent
// kernel, thread-block clusters). The arithmetic is the same either way, and
// the CPU backend ignores them all. Measurements: docs/tuning/execution.md.
#pragma once

#include <cstddef>

namespace gpusolve::rbd {

struct ExecutionSettings {
  // Collision detection runs as one CUDA graph, captured once and launched
  // again while the bodies, the contacts' storage, the margin and the friction
  // stay (its kernels read the step's counts from device memory).
  bool detection_graph = true;
  // Where the persistent kernel is not used, a Jacobi-family solve's runs of
  // iterations between two residual checks are captured into CUDA graphs,
  // updated in place and replayed. Off: a run's arguments change every step.
  bool graphs = false;
  // A Jacobi-family solve (substepping too) with at most this many contacts runs
  // as one cooperative kernel, its phases separated by grid-wide barriers, its
  // checks and retries inside; above it, or at 0, a launch per phase. It takes
  // precedence over `graphs`.
  std::size_t persistent_max_contacts = 1000000;
  // A persistent grid that fits in one thread-block cluster (sm_90 and later, at
  // most 16 blocks) runs as that cluster, with the cluster's hardware barrier.
  bool persistent_clusters = true;
  // Every this many steps, World puts its bodies in spatial order
  // (World::reorder_bodies; advance_unattended waits for the steps before
  // each); 0: never. The BodySet's indices keep naming the same bodies. Off
  // until a GPU measures what it buys.
  std::size_t reorder_every = 0;

  void validate() const {}  // every value is meaningful
};

}  // namespace gpusolve::rbd
