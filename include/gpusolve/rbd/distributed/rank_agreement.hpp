// RankAgreement: a failure on one rank becomes the same error on every rank,
// so that no rank waits for a collective that the failing one never reaches.
#pragma once

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include <mpi.h>

#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/distributed/rank_failure.hpp"

namespace gpusolve::rbd {

// run(f) on every rank of the communicator (a collective): when f throws on
// any rank, every rank throws the error of the lowest rank that failed
// (RankFailure::throw_from: the library's errors as their own type, else a
// RankFailedError naming that rank). With an `alarm`, its waits
// also end when another rank raises one (RankAlarm).
class RankAgreement {
 public:
  explicit RankAgreement(MPI_Comm comm, RankAlarm* alarm = nullptr) : comm_(comm), alarm_(alarm) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
  }

  template <class F>
  void run(F&& f) const {
    RankFailure mine;
    try {
      f();
    } catch (const std::exception&) {
      mine = RankFailure::current();
    }
    int first = mine.kind != RankFailure::Kind::none ? rank_ : ranks_;
    if (alarm_ != nullptr)
      alarm_->allreduce(&first, 1, MPI_INT, MPI_MIN, comm_);
    else
      MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm_);
    if (first == ranks_) return;
    const RankFailure agreed = RankFailure::unpack(broadcast(mine.pack(), first));
    if (alarm_ != nullptr) alarm_->agreed();
    agreed.throw_from(first);
  }

 private:
  // `mine` on rank `root`, on every rank.
  std::vector<char> broadcast(std::vector<char> mine, int root) const {
    std::uint64_t size = mine.size();
    bcast(&size, int(sizeof size), root);
    mine.resize(std::size_t(size));
    bcast(mine.data(), int(size), root);
    return mine;
  }
  void bcast(void* data, int bytes, int root) const {
    if (alarm_ != nullptr)
      alarm_->broadcast(data, bytes, root, comm_);
    else
      MPI_Bcast(data, bytes, MPI_BYTE, root, comm_);
  }

  MPI_Comm comm_;
  RankAlarm* alarm_;
  int rank_ = 0, ranks_ = 1;
};

}  // namespace gpusolve::rbd
