// MpiBodyExchange: a BodyExchange over MPI between the ranks of a distributed
// world (host memory: the CPU backend).
#pragma once

#include <chrono>
#include <cstddef>
#include <utility>
#include <vector>

#include <mpi.h>

#include "gpusolve/rbd/execution/body_exchange.hpp"

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
}  // namespace detail

// Which local bodies a rank shares with each other rank, set after every
// exchange of bodies: shadows[r], the local indices of this rank's shadows of
// bodies rank r owns; copies[r], the local indices of this rank's bodies that
// rank r holds as shadows, both in the order in which the bodies were sent.
struct SharedBodies {
  std::vector<std::vector<std::size_t>> shadows, copies;
};

// combine(): every shadow's sums go to its owner, which adds them to its own
// in the order of the ranks (deterministic), and the totals go back to every
// rank that holds a shadow of the body: two all-to-all exchanges of six values
// per shared body. reduce(): MPI_Allreduce. Counts the seconds it spends.
template <class T>
class MpiBodyExchange final : public BodyExchange<T> {
 public:
  explicit MpiBodyExchange(MPI_Comm comm) : comm_(comm) {
    MPI_Comm_size(comm, &ranks_);
    shared_.shadows.assign(ranks_, {});
    shared_.copies.assign(ranks_, {});
  }

  void share(SharedBodies shared) { shared_ = std::move(shared); }

  void combine(T* sums, std::size_t pitch, std::size_t, stream_t) override {
    const auto start = std::chrono::steady_clock::now();
    // Partial sums of the shadows up to their owners ...
    pack(sums, pitch, shared_.shadows, out_, out_counts_, out_offsets_);
    layout(shared_.copies, in_, in_counts_, in_offsets_);
    all_to_all();
    unpack(sums, pitch, shared_.copies, true);
    // ... and the owners' totals back to every shadow.
    pack(sums, pitch, shared_.copies, out_, out_counts_, out_offsets_);
    layout(shared_.shadows, in_, in_counts_, in_offsets_);
    all_to_all();
    unpack(sums, pitch, shared_.shadows, false);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void reduce(T* value, ExchangeOp op, stream_t) override {
    const auto start = std::chrono::steady_clock::now();
    MPI_Allreduce(MPI_IN_PLACE, value, 1, detail::mpi_type<T>(), op == ExchangeOp::maximum ? MPI_MAX : MPI_SUM,
                  comm_);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // Seconds spent in combine() and reduce() since the last call.
  double take_seconds() {
    const double s = seconds_;
    seconds_ = 0;
    return s;
  }

 private:
  static constexpr std::size_t values = 6;  // dv, dw

  void pack(const T* sums, std::size_t pitch, const std::vector<std::vector<std::size_t>>& lists, std::vector<T>& out,
            std::vector<int>& counts, std::vector<int>& offsets) const {
    layout(lists, out, counts, offsets);
    for (int r = 0; r < ranks_; ++r)
      for (std::size_t k = 0; k < lists[r].size(); ++k)
        for (std::size_t c = 0; c < values; ++c)
          out[std::size_t(offsets[r]) + k * values + c] = sums[c * pitch + lists[r][k]];
  }
  // What came, rank by rank, into the rows of `lists`: added to an owner's
  // own sums (`add`), or in place of a shadow's.
  void unpack(T* sums, std::size_t pitch, const std::vector<std::vector<std::size_t>>& lists, bool add) const {
    for (int r = 0; r < ranks_; ++r)
      for (std::size_t k = 0; k < lists[r].size(); ++k)
        for (std::size_t c = 0; c < values; ++c) {
          T& x = sums[c * pitch + lists[r][k]];
          const T y = in_[std::size_t(in_offsets_[r]) + k * values + c];
          x = add ? x + y : y;
        }
  }
  void layout(const std::vector<std::vector<std::size_t>>& lists, std::vector<T>& buffer, std::vector<int>& counts,
              std::vector<int>& offsets) const {
    counts.assign(ranks_, 0);
    offsets.assign(ranks_, 0);
    int total = 0;
    for (int r = 0; r < ranks_; ++r) {
      counts[r] = int(lists[r].size() * values);
      offsets[r] = total;
      total += counts[r];
    }
    buffer.resize(std::size_t(total));
  }
  void all_to_all() {
    MPI_Alltoallv(out_.data(), out_counts_.data(), out_offsets_.data(), detail::mpi_type<T>(), in_.data(),
                  in_counts_.data(), in_offsets_.data(), detail::mpi_type<T>(), comm_);
  }

  MPI_Comm comm_;
  int ranks_ = 1;
  SharedBodies shared_;
  std::vector<T> out_, in_;
  std::vector<int> out_counts_, out_offsets_, in_counts_, in_offsets_;
  double seconds_ = 0;
};

}  // namespace gpusolve::rbd
