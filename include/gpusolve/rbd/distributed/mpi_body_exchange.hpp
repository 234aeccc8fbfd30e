// MpiBodyExchange: the exchange of a distributed world through host memory
// with MPI, on either backend: the shared bodies' values are packed where the
// bodies live, copied to the host and sent to the ranks that share them
// (MPI_Isend and MPI_Irecv, so a rank waits on its neighbours only, not on
// every rank as an all-to-all does); reductions are MPI_Allreduce. Each call
// waits for the backend's stream, and its waits end where another rank raises
// the alarm (RankAlarm). Its messages go through a duplicate of the communicator.
#pragma once

#include <cstddef>
#include <vector>

#include <mpi.h>

#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/distributed/body_sum_exchange.hpp"
#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/distributed/rank_communicator.hpp"
#include "gpusolve/rbd/execution/backend.hpp"

namespace gpusolve::rbd {

namespace detail {
template <class T>
MPI_Datatype mpi_type();
template <>
inline MPI_Datatype mpi_type<float>() {
  return MPI_FLOAT;
}
template <>
inline MPI_Datatype mpi_type<double>() {
  return MPI_DOUBLE;
}

inline MPI_Op mpi_op(ExchangeOp op) {
  return op == ExchangeOp::maximum ? MPI_MAX : op == ExchangeOp::minimum ? MPI_MIN : MPI_SUM;
}
}  // namespace detail

// BodySumExchange's transport through host memory.
template <class Device, class T>
class MpiTransport {
 public:
  MpiTransport(MPI_Comm comm, RankAlarm* alarm) : comm_(comm), alarm_(alarm), ranks_(comm_.ranks()) {}

  int ranks() const { return ranks_; }

  void send(const T* out, const std::vector<std::size_t>& out_counts, const std::vector<std::size_t>& out_offsets,
            T* in, const std::vector<std::size_t>& in_counts, const std::vector<std::size_t>& in_offsets,
            stream_t stream) {
    const std::size_t out_n = total(out_counts), in_n = total(in_counts);
    out_host_.resize(out_n), in_host_.resize(in_n);
    detail::copy_with_host<Device>(out_host_.data(), out, out_n, true, stream);
    requests_.clear();
    for (int r = 0; r < ranks_; ++r)
      if (in_counts[r] != 0)
        MPI_Irecv(in_host_.data() + in_offsets[r], int(in_counts[r]), detail::mpi_type<T>(), r, 0, comm_,
                  &requests_.emplace_back());
    for (int r = 0; r < ranks_; ++r)
      if (out_counts[r] != 0)
        MPI_Isend(out_host_.data() + out_offsets[r], int(out_counts[r]), detail::mpi_type<T>(), r, 0, comm_,
                  &requests_.emplace_back());
    if (alarm_ != nullptr)
      alarm_->wait(requests_);
    else
      MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    detail::copy_with_host<Device>(in, in_host_.data(), in_n, false, stream);
  }

  void reduce(T* value, ExchangeOp op, stream_t stream) {
    T x = detail::read_back<Device>(value, 0, stream);
    if (alarm_ != nullptr)
      alarm_->allreduce(&x, 1, detail::mpi_type<T>(), detail::mpi_op(op), comm_);
    else
      MPI_Allreduce(MPI_IN_PLACE, &x, 1, detail::mpi_type<T>(), detail::mpi_op(op), comm_);
    detail::copy_with_host<Device>(value, &x, 1, false, stream);
  }

 private:
  static std::size_t total(const std::vector<std::size_t>& counts) {
    std::size_t n = 0;
    for (std::size_t c : counts) n += c;
    return n;
  }

  RankCommunicator comm_;
  RankAlarm* alarm_;
  int ranks_ = 1;
  std::vector<T> out_host_, in_host_;  // the values on the host, for MPI
  std::vector<MPI_Request> requests_;
};

template <class Device, class T>
using MpiBodyExchange = BodySumExchange<Device, T, MpiTransport<Device, T>>;

}  // namespace gpusolve::rbd
