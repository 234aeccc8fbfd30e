// BodyExchange: what a solve shares with the other ranks that hold copies of
// its bodies. rbd/distributed/ implements it over MPI; a World without one
// shares nothing, and no solver header learns about ranks.
#pragma once

#include <cstddef>

#include "gpusolve/core/launch.hpp"

namespace gpusolve::rbd {

// The reductions a rank's solve needs to agree with the others.
enum class ExchangeOp { maximum, sum };

template <class T>
class BodyExchange {
 public:
  virtual ~BodyExchange() = default;
  // `sums` (bodies x 6 values, row r at sums + r * pitch, in the backend's
  // memory): each body's velocity changes of this iteration (dv, then dw), as
  // this rank's contacts made them. Afterwards every rank that holds the body
  // holds its sum over all ranks.
  virtual void combine(T* sums, std::size_t pitch, std::size_t bodies, stream_t stream) = 0;
  // *value (in the backend's memory), this rank's reduction: its `op` over the ranks.
  virtual void reduce(T* value, ExchangeOp op, stream_t stream) = 0;
};

}  // namespace gpusolve::rbd
