// RankMessages: records of a trivially copyable type between the ranks of a
// communicator, as bytes: sparse exchanges between the ranks that have
// something to send, and MPI's gathers.
#pragma once

#include <algorithm>
#include <climits>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <mpi.h>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/distributed/rank_communicator.hpp"

namespace gpusolve::rbd {

namespace detail {

// MPI's type for one record of E, its bytes as one unit, so that MPI's int
// counts and displacements count records, not bytes: a message may pass
// 2^31 bytes (15 million bodies), as the ranks of a billion-body scene send.
template <class E>
class RecordType {
 public:
  RecordType() {
    MPI_Type_contiguous(int(sizeof(E)), MPI_BYTE, &type_);
    MPI_Type_commit(&type_);
  }
  ~RecordType() { MPI_Type_free(&type_); }
  RecordType(const RecordType&) = delete;
  RecordType& operator=(const RecordType&) = delete;
  operator MPI_Datatype() const { return type_; }

 private:
  MPI_Datatype type_;
};

// n records as MPI's count, or UnsupportedError where MPI's int cannot hold it.
inline int record_count(std::size_t n) {
  if (n > std::size_t(INT_MAX))
    throw UnsupportedError("gpusolve: RankMessages: " + std::to_string(n) +
                           " records in one message or gather, more than MPI's counts hold (2^31 - 1)");
  return int(n);
}

}  // namespace detail

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
    const detail::RecordType<E> record;
    for (const std::vector<E>& message : to) detail::record_count(message.size());  // before any is sent
    std::vector<MPI_Request> sends;
    for (int r = 0; r < ranks_; ++r)
      if (!to[r].empty()) {
        sends.emplace_back();
        MPI_Issend(to[r].data(), detail::record_count(to[r].size()), record, r, tag, comm_, &sends.back());
      }
    std::vector<std::pair<int, std::vector<E>>> came;  // (rank, records)
    MPI_Request barrier = MPI_REQUEST_NULL;
    for (bool in_barrier = false, done = false; !done;) {
      if (alarm_ != nullptr) alarm_->check();
      int found = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, tag, comm_, &found, &status);
      if (found) {
        int records = 0;
        MPI_Get_count(&status, record, &records);
        came.emplace_back(status.MPI_SOURCE, std::vector<E>(std::size_t(records)));
        MPI_Recv(came.back().second.data(), records, record, status.MPI_SOURCE, tag, comm_, MPI_STATUS_IGNORE);
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
    const detail::RecordType<E> record;
    const int count = detail::record_count(mine.size());
    std::vector<int> counts(ranks_), at(ranks_);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
    std::vector<E> all(offsets(counts, at));
    MPI_Allgatherv(mine.data(), count, record, all.data(), counts.data(), at.data(), record, comm_);
    return all;
  }

  // Every rank's records, rank by rank, on rank `root` (empty elsewhere).
  template <class E>
  std::vector<E> gather_to(const std::vector<E>& mine, int root) const {
    static_assert(std::is_trivially_copyable_v<E>);
    const detail::RecordType<E> record;
    const int count = detail::record_count(mine.size());
    std::vector<int> counts(ranks_), at(ranks_);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);  // every rank checks the displacements
    const std::size_t total = offsets(counts, at);
    std::vector<E> all(rank_ == root ? total : 0);
    MPI_Gatherv(mine.data(), count, record, all.data(), counts.data(), at.data(), record, root, comm_);
    return all;
  }

 private:
  // Each rank's offset (in records) from its count; returns the total. A
  // displacement past MPI's int is refused (detail::record_count).
  std::size_t offsets(const std::vector<int>& counts, std::vector<int>& at) const {
    std::size_t total = 0;
    for (int r = 0; r < ranks_; ++r) at[r] = detail::record_count(total), total += std::size_t(counts[r]);
    return total;
  }

  RankCommunicator comm_;
  RankAlarm* alarm_;
  int rank_ = 0, ranks_ = 1;
  unsigned rounds_ = 0;  // exchanges so far (the same count on every rank)
};

}  // namespace gpusolve::rbd
