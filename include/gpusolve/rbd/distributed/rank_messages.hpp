// RankMessages: records of a trivially copyable type between the ranks of a
// communicator, as bytes: sparse exchanges between the ranks that have
// something to send, and MPI's gathers.
#pragma once

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpi.h>

#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/distributed/rank_communicator.hpp"

namespace gpusolve::rbd {

class RankMessages {
 public:
  // Its messages go through a duplicate of `comm` (a collective), apart from
  // any other traffic; exchange() heeds `alarm` while it waits (RankAlarm).
  explicit RankMessages(MPI_Comm comm, RankAlarm* alarm = nullptr)
      : comm_(comm), alarm_(alarm), rank_(comm_.rank()), ranks_(comm_.ranks()) {}

  // Sends to[r] to rank r; returns what came, rank by rank, each rank's
  // records in the order it sent them (`from`, if given: each record's rank).
  // A collective, but only ranks with records for each other exchange
  // messages: Hoefler, Siebert and Lumsdaine's non-blocking consensus (2010,
  // "Scalable communication protocols for dynamic sparse data exchange"):
  // synchronous sends, received as they are found, until a non-blocking
  // barrier entered once a rank's own sends were all received completes.
  template <class E>
  std::vector<E> exchange(const std::vector<std::vector<E>>& to, std::vector<int>* from = nullptr) {
    static_assert(std::is_trivially_copyable_v<E>);
    // Two rounds in a row can overlap (a rank may send the next round's
    // messages before another has seen this round's barrier end), never three.
    const int tag = 1 + int(rounds_++ % 2);
    std::vector<MPI_Request> sends;
    for (int r = 0; r < ranks_; ++r)
      if (!to[r].empty()) {
        sends.emplace_back();
        MPI_Issend(to[r].data(), int(to[r].size() * sizeof(E)), MPI_BYTE, r, tag, comm_, &sends.back());
      }
    std::vector<std::pair<int, std::vector<E>>> came;  // (rank, records)
    MPI_Request barrier = MPI_REQUEST_NULL;
    for (bool in_barrier = false, done = false; !done;) {
      if (alarm_ != nullptr) alarm_->check();
      int found = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, tag, comm_, &found, &status);
      if (found) {
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        came.emplace_back(status.MPI_SOURCE, std::vector<E>(std::size_t(bytes) / sizeof(E)));
        MPI_Recv(came.back().second.data(), bytes, MPI_BYTE, status.MPI_SOURCE, tag, comm_, MPI_STATUS_IGNORE);
      }
      int complete = 0;
      if (in_barrier) {
        MPI_Test(&barrier, &complete, MPI_STATUS_IGNORE);
        done = complete != 0;
      } else {
        MPI_Testall(int(sends.size()), sends.data(), &complete, MPI_STATUSES_IGNORE);
        if (complete) MPI_Ibarrier(comm_, &barrier), in_barrier = true;
      }
    }
    std::sort(came.begin(), came.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<E> in;
    if (from != nullptr) from->clear();
    for (const auto& [rank, records] : came) {
      in.insert(in.end(), records.begin(), records.end());
      if (from != nullptr) from->insert(from->end(), records.size(), rank);
    }
    return in;
  }

  // Every rank's records, rank by rank, on every rank.
  template <class E>
  std::vector<E> all_gather(const std::vector<E>& mine) const {
    static_assert(std::is_trivially_copyable_v<E>);
    const int bytes = int(mine.size() * sizeof(E));
    std::vector<int> counts(ranks_), at(ranks_);
    MPI_Allgather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
    std::vector<E> all(offsets(counts, at) / sizeof(E));
    MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), at.data(), MPI_BYTE, comm_);
    return all;
  }

  // Every rank's records, rank by rank, on rank `root` (empty elsewhere).
  template <class E>
  std::vector<E> gather_to(const std::vector<E>& mine, int root) const {
    static_assert(std::is_trivially_copyable_v<E>);
    const int bytes = int(mine.size() * sizeof(E));
    std::vector<int> counts(ranks_), at(ranks_);
    MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, root, comm_);
    const std::size_t total = offsets(counts, at);
    std::vector<E> all(rank_ == root ? total / sizeof(E) : 0);
    MPI_Gatherv(mine.data(), bytes, MPI_BYTE, all.data(), counts.data(), at.data(), MPI_BYTE, root, comm_);
    return all;
  }

 private:
  // Each rank's offset from its count; returns the total.
  std::size_t offsets(const std::vector<int>& counts, std::vector<int>& at) const {
    int total = 0;
    for (int r = 0; r < ranks_; ++r) at[r] = total, total += counts[r];
    return std::size_t(total);
  }

  RankCommunicator comm_;
  RankAlarm* alarm_;
  int rank_ = 0, ranks_ = 1;
  unsigned rounds_ = 0;  // exchanges so far (the same count on every rank)
};

}  // namespace gpusolve::rbd
