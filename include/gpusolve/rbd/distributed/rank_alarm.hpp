// RankAlarm: a failure on one rank ends the other ranks' waits. Where one
// rank throws while the others go on into an exchange that needs it (its
// World ran out of memory inside a step, a launch failed), it raises the
// alarm: a message to every other rank on a communicator of the alarm's own,
// sent without waiting. The distributed world's waits (for messages, for
// reductions) look for it while they wait and throw that failure
// (RankFailure::throw_from) instead of waiting for a rank that will not come.
// After a failure the communicators are abandoned, never freed
// (RankCommunicator::abandon_all): what was pending on them stays pending.
#pragma once

#include <cstring>
#include <memory>
#include <vector>

#include <mpi.h>

#include "gpusolve/rbd/distributed/rank_communicator.hpp"
#include "gpusolve/rbd/distributed/rank_failure.hpp"

namespace gpusolve::rbd {

class RankAlarm {
 public:
  explicit RankAlarm(MPI_Comm comm) : comm_(comm) {}
  RankAlarm(const RankAlarm&) = delete;
  RankAlarm& operator=(const RankAlarm&) = delete;
  ~RankAlarm() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized)
      for (MPI_Request& r : sent_) MPI_Request_free(&r);
  }

  // f(); where it throws a failure of this rank's own (not one every rank
  // already shares: heard from another rank, or agreed()), every other rank
  // is told before it propagates.
  template <class F>
  decltype(auto) guard(F&& f) {
    shared_ = false;
    try {
      return f();
    } catch (...) {
      if (!shared_) raise(RankFailure::current());
      throw;
    }
  }

  // The failure being thrown is every rank's already (RankAgreement): guard() raises nothing.
  void agreed() { shared_ = true; }

  // Throws the failure another rank raised, if one has come.
  void check() {
    int found = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, tag_, comm_, &found, &status);
    if (!found) return;
    int size = 0;
    MPI_Get_count(&status, MPI_BYTE, &size);
    std::vector<char> notice(std::size_t(size > 0 ? size : 0));
    MPI_Recv(notice.data(), size, MPI_BYTE, status.MPI_SOURCE, tag_, comm_, MPI_STATUS_IGNORE);
    shared_ = true;
    RankCommunicator::abandon_all();
    RankFailure::unpack(notice).throw_from(status.MPI_SOURCE);
  }

  // Waits for point-to-point `requests`, or throws check()'s failure; the
  // requests still pending then are cancelled.
  void wait(std::vector<MPI_Request>& requests) {
    for (;;) {
      int done = 0;
      MPI_Testall(int(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
      if (done) return;
      try {
        check();
      } catch (...) {
        for (MPI_Request& r : requests)
          if (r != MPI_REQUEST_NULL) MPI_Cancel(&r), MPI_Request_free(&r);
        throw;
      }
    }
  }

  // MPI_Allreduce of `count` values at `inout` over `comm`, or throws
  // check()'s failure while it waits. A reduction abandoned so keeps a copy
  // of its values that is never freed (MPI may still write into it).
  void allreduce(void* inout, int count, MPI_Datatype type, MPI_Op op, MPI_Comm comm) {
    int size = 0;
    MPI_Type_size(type, &size);
    const std::size_t bytes = std::size_t(size) * std::size_t(count);
    auto values = std::make_unique<char[]>(bytes);
    std::memcpy(values.get(), inout, bytes);
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, values.get(), count, type, op, comm, &request);
    collective(request, values);
    std::memcpy(inout, values.get(), bytes);
  }

  // MPI_Bcast of `bytes` at `data` from `root` over `comm`, as allreduce() waits.
  void broadcast(void* data, int bytes, int root, MPI_Comm comm) {
    auto values = std::make_unique<char[]>(std::size_t(bytes > 0 ? bytes : 0));
    std::memcpy(values.get(), data, std::size_t(bytes > 0 ? bytes : 0));
    MPI_Request request;
    MPI_Ibcast(values.get(), bytes, MPI_BYTE, root, comm, &request);
    collective(request, values);
    std::memcpy(data, values.get(), std::size_t(bytes > 0 ? bytes : 0));
  }

 private:
  static constexpr int tag_ = 1;

  // Tells every other rank of `failure`, without waiting (once: the first failure).
  void raise(const RankFailure& failure) {
    if (!notice_.empty()) return;
    RankCommunicator::abandon_all();
    notice_ = failure.pack();
    for (int r = 0; r < comm_.ranks(); ++r)
      if (r != comm_.rank()) MPI_Isend(notice_.data(), int(notice_.size()), MPI_BYTE, r, tag_, comm_, &sent_.emplace_back());
  }

  // Waits for a collective's request; where a failure is heard, its buffer is let go unfreed.
  void collective(MPI_Request& request, std::unique_ptr<char[]>& values) {
    for (;;) {
      int done = 0;
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) return;
      try {
        check();
      } catch (...) {
        values.release();
        throw;
      }
    }
  }

  RankCommunicator comm_;  // the alarm's messages
  bool shared_ = false;  // guard()'s failure is every rank's already (heard, or agreed)
  std::vector<char> notice_;  // this rank's failure, while its sends are pending
  std::vector<MPI_Request> sent_;
};

}  // namespace gpusolve::rbd
