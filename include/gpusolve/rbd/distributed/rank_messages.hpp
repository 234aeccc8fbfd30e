// RankMessages: records of a trivially copyable type between the ranks of a
// communicator, as bytes (MPI's collectives, with the counts exchanged first).
#pragma once

#include <cstddef>
#include <type_traits>
#include <vector>

#include <mpi.h>

namespace gpusolve::rbd {

class RankMessages {
 public:
  explicit RankMessages(MPI_Comm comm) : comm_(comm) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
  }

  // Sends to[r] to rank r; returns what came, rank by rank.
  template <class E>
  std::vector<E> all_to_all(const std::vector<std::vector<E>>& to) const {
    static_assert(std::is_trivially_copyable_v<E>);
    std::vector<int> out_counts(ranks_), out_offsets(ranks_), in_counts(ranks_), in_offsets(ranks_);
    std::vector<E> out;
    for (int r = 0; r < ranks_; ++r) {
      out_offsets[r] = int(out.size() * sizeof(E));
      out_counts[r] = int(to[r].size() * sizeof(E));
      out.insert(out.end(), to[r].begin(), to[r].end());
    }
    MPI_Alltoall(out_counts.data(), 1, MPI_INT, in_counts.data(), 1, MPI_INT, comm_);
    std::vector<E> in(offsets(in_counts, in_offsets) / sizeof(E));
    MPI_Alltoallv(out.data(), out_counts.data(), out_offsets.data(), MPI_BYTE, in.data(), in_counts.data(),
                  in_offsets.data(), MPI_BYTE, comm_);
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

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
};

}  // namespace gpusolve::rbd
