// RankCommunicator: a duplicate of an MPI communicator (a collective), freed
// with it, so that one part's messages never meet another part's or the user's.
#pragma once

#include <mpi.h>

namespace gpusolve::rbd {

class RankCommunicator {
 public:
  explicit RankCommunicator(MPI_Comm comm) {
    MPI_Comm_dup(comm, &comm_);
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_);
  }
  RankCommunicator(const RankCommunicator&) = delete;
  RankCommunicator& operator=(const RankCommunicator&) = delete;
  ~RankCommunicator() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && !abandoned()) MPI_Comm_free(&comm_);
  }

  // After a failure that left messages pending (RankAlarm), this process
  // frees no communicator any more: MPI may give a freed one's context to a
  // new communicator, which would then receive what was left pending.
  static void abandon_all() { abandoned() = true; }

  operator MPI_Comm() const { return comm_; }
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }

 private:
  static bool& abandoned() {
    static bool all = false;
    return all;
  }

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, ranks_ = 1;
};

}  // namespace gpusolve::rbd
