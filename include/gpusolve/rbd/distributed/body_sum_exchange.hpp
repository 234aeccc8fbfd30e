// BodySumExchange: the BodyExchange of a distributed world, over a transport
// between its ranks. combine() sends every shadow's sums to its owner, which
// adds them to its own in the order of the ranks (a launch per rank:
// deterministic), and sends the totals back to every rank that holds a shadow
// of the body: two exchanges of six values per shared body between the ranks
// that share it, packed
// and unpacked where the bodies live. The transport moves them: through host
// memory with MPI (mpi_body_exchange.hpp) or between GPUs with NCCL
// (nccl_body_exchange.hpp).
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <mpi.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/rbd/distributed/rank_alarm.hpp"
#include "gpusolve/rbd/execution/body_exchange.hpp"

namespace gpusolve::rbd {

namespace detail {

inline constexpr std::size_t exchanged_values = 6;  // dv, dw

// Entry k of a list of bodies: its six sums into out[6k, 6k + 6).
template <class T>
struct PackSums {
  VectorD2View<T> sums;
  const std::uint32_t* bodies;
  T* out;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    for (std::size_t c = 0; c < exchanged_values; ++c) out[k * exchanged_values + c] = sums(bodies[k], c);
  }
};

// Entry k of a list of bodies: in[6k, 6k + 6) added to its sums, or in their place.
template <class T>
struct UnpackSums {
  VectorD2View<T> sums;
  const std::uint32_t* bodies;
  const T* in;
  bool add;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    for (std::size_t c = 0; c < exchanged_values; ++c) {
      const T x = in[k * exchanged_values + c];
      sums(bodies[k], c) = add ? sums(bodies[k], c) + x : x;
    }
  }
};

}  // namespace detail

// Which local bodies a rank shares with each other rank, set after every
// exchange of bodies: shadows[r], the local indices of this rank's shadows of
// bodies rank r owns; copies[r], the local indices of this rank's bodies that
// rank r holds as shadows, both in the order in which the bodies were sent.
struct SharedBodies {
  std::vector<std::vector<std::size_t>> shadows, copies;
};

// What a distributed world asks of its exchange besides a solve's: which
// bodies are shared, and the seconds its calls took.
template <class T>
class RankExchange : public BodyExchange<T> {
 public:
  // The bodies shared from now on (after an exchange of bodies).
  virtual void share(const SharedBodies& shared) = 0;
  // Seconds spent in combine() and reduce() since the last call: waits
  // included where the transport waits (MPI); the time to queue where it
  // does not (NCCL, whose exchanges show in the solve's time).
  virtual double take_seconds() = 0;
};

// Transport: `Transport(MPI_Comm, RankAlarm*)` (the alarm its waits heed,
// where it waits on the host), `int ranks()`,
// `send(out, out_counts, out_offsets, in, in_counts, in_offsets, stream)`
// (values of type T in the backend's memory: out's block for each rank to it,
// each rank's block into in) and `reduce(value, op, stream)` (*value over the
// ranks, in place).
template <class Device, class T, class Transport>
class BodySumExchange final : public RankExchange<T> {
 public:
  explicit BodySumExchange(MPI_Comm comm, RankAlarm* alarm = nullptr) : transport_(comm, alarm) {
    const int ranks = transport_.ranks();
    share({std::vector<std::vector<std::size_t>>(ranks), std::vector<std::vector<std::size_t>>(ranks)});
  }

  void share(const SharedBodies& shared) override {
    shadows_ = List(shared.shadows);
    copies_ = List(shared.copies);
  }

  VectorD2View<T> sums(std::size_t bodies) override {
    if (store_.size_x() < exchanged * bodies) store_.resize(exchanged * bodies);
    return {store_.data(), bodies, exchanged, bodies};
  }

  void combine(std::size_t bodies, stream_t stream) override {
    const auto start = std::chrono::steady_clock::now();
    const VectorD2View<T> s = sums(bodies);
    // Partial sums of the shadows up to their owners, added rank by rank ...
    send(s, shadows_, copies_, stream);
    for (int r = 0; r < transport_.ranks(); ++r)
      if (const std::size_t n = copies_.count(r))
        launch(Device{}, n,
               detail::UnpackSums<T>{s, copies_.bodies.data() + copies_.first[r],
                                     in_.data() + exchanged * copies_.first[r], true},
               stream);
    // ... and the owners' totals back to every shadow.
    send(s, copies_, shadows_, stream);
    if (const std::size_t n = shadows_.total())
      launch(Device{}, n, detail::UnpackSums<T>{s, shadows_.bodies.data(), in_.data(), false}, stream);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void reduce(T* value, ExchangeOp op, stream_t stream) override {
    const auto start = std::chrono::steady_clock::now();
    transport_.reduce(value, op, stream);
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  double take_seconds() override {
    const double s = seconds_;
    seconds_ = 0;
    return s;
  }

 private:
  static constexpr std::size_t exchanged = detail::exchanged_values;

  // Local body indices grouped by rank: rank r's at [first[r], first[r + 1])
  // of `bodies`, on the backend.
  struct List {
    VectorD1<std::uint32_t, device_is<Device>> bodies;
    std::vector<std::size_t> first{0};
    List() = default;
    explicit List(const std::vector<std::vector<std::size_t>>& by_rank) {
      std::vector<std::uint32_t> flat;
      for (const auto& l : by_rank) {
        flat.insert(flat.end(), l.begin(), l.end());
        first.push_back(flat.size());
      }
      bodies.resize(flat.size());
      detail::copy_with_host<Device>(bodies.data(), flat.data(), flat.size(), false, stream_t{});
    }
    std::size_t count(int r) const { return first[r + 1] - first[r]; }
    std::size_t total() const { return first.back(); }
  };

  // The values of `from`'s bodies to their ranks; those of `into`'s bodies
  // arrive in in_ in its order.
  void send(const VectorD2View<T>& s, const List& from, const List& into, stream_t stream) {
    const std::size_t out_n = exchanged * from.total(), in_n = exchanged * into.total();
    if (packed_.size_x() < out_n) packed_.resize(out_n);
    if (in_.size_x() < in_n) in_.resize(in_n);
    if (from.total() != 0)
      launch(Device{}, from.total(), detail::PackSums<T>{s, from.bodies.data(), packed_.data()}, stream);
    const int ranks = transport_.ranks();
    std::vector<std::size_t> out_counts(ranks), out_offsets(ranks), in_counts(ranks), in_offsets(ranks);
    for (int r = 0; r < ranks; ++r) {
      out_counts[r] = exchanged * from.count(r), out_offsets[r] = exchanged * from.first[r];
      in_counts[r] = exchanged * into.count(r), in_offsets[r] = exchanged * into.first[r];
    }
    transport_.send(packed_.data(), out_counts, out_offsets, in_.data(), in_counts, in_offsets, stream);
  }

  Transport transport_;
  List shadows_, copies_;
  VectorD1<T, device_is<Device>> store_;        // sums(): bodies x 6, one row of bodies per value
  VectorD1<T, device_is<Device>> packed_, in_;  // the values sent and received, on the backend
  double seconds_ = 0;
};

}  // namespace gpusolve::rbd
