// BodyExchange: what a solve shares with the other ranks that hold copies of
// its bodies. rbd/distributed/ implements it over MPI; a World without one
// shares nothing, and no solver header learns about ranks.
#pragma once

#include <cstddef>

#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/launch.hpp"

namespace gpusolve::rbd {

// The reductions a rank's solve needs to agree with the others.
enum class ExchangeOp { maximum, minimum, sum };

template <class T>
class BodyExchange {
 public:
  virtual ~BodyExchange() = default;
  // combine()'s store, kept by the exchange: `bodies` x 6 values in the
  // backend's memory, each body's velocity changes of this iteration (dv, then dw).
  virtual VectorD2View<T> sums(std::size_t bodies) = 0;
  // The store holds each body's changes as this rank's contacts made them;
  // afterwards every rank that holds the body holds their sum over all ranks.
  virtual void combine(std::size_t bodies, stream_t stream) = 0;
  // *value (in the backend's memory), this rank's reduction: its `op` over the ranks.
  virtual void reduce(T* value, ExchangeOp op, stream_t stream) = 0;
};

}  // namespace gpusolve::rbd
