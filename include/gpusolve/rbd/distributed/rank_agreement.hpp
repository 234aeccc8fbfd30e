// RankAgreement: a failure on one rank becomes the same error on every rank,
// so that no rank waits for a collective that the failing one never reaches.
#pragma once

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include <mpi.h>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"

namespace gpusolve::rbd {

// An error that another rank threw, not a body's (those are rethrown as their
// own type): its rank and message.
class RankFailedError : public Error {
 public:
  RankFailedError(int rank, const std::string& what)
      : Error("gpusolve: rank " + std::to_string(rank) + ": " + what), rank_(rank) {}
  int rank() const noexcept { return rank_; }

 private:
  int rank_;
};

// run(f) on every rank of the communicator (a collective): when f throws on
// any rank, every rank throws the error of the lowest rank that failed, as a
// NonFiniteStateError or InvalidBodyError with the same body, field and step
// where it was one of those, else as a RankFailedError naming that rank.
class RankAgreement {
 public:
  explicit RankAgreement(MPI_Comm comm) : comm_(comm) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &ranks_);
  }

  template <class F>
  void run(F&& f) const {
    Failure mine;
    try {
      f();
    } catch (const NonFiniteStateError& e) {
      mine = {Kind::non_finite, e.body(), e.step(), e.field(), why(e)};
    } catch (const InvalidBodyError& e) {
      mine = {Kind::invalid_body, e.body(), 0, e.field(), why(e)};
    } catch (const std::exception& e) {
      mine = {Kind::other, 0, 0, "", e.what()};
    }
    int first = mine.kind != Kind::none ? rank_ : ranks_;
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm_);
    if (first == ranks_) return;
    const Failure f_first = broadcast(mine, first);
    if (f_first.kind == Kind::non_finite) throw NonFiniteStateError(f_first.body, f_first.field, f_first.step);
    if (f_first.kind == Kind::invalid_body) throw InvalidBodyError(f_first.body, f_first.field, f_first.why);
    throw RankFailedError(first, f_first.why);
  }

 private:
  enum class Kind : int { none, non_finite, invalid_body, other };
  struct Failure {
    Kind kind = Kind::none;
    std::size_t body = 0, step = 0;
    std::string field, why;
  };

  // An InvalidBodyError's reason, without the "body N, field `f`: " its message starts with.
  static std::string why(const InvalidBodyError& e) {
    const std::string w = e.what();
    const std::size_t p = w.find("`: ");
    return p == std::string::npos ? w : w.substr(p + 3);
  }

  Failure broadcast(const Failure& mine, int root) const {
    std::uint64_t head[5] = {std::uint64_t(mine.kind), mine.body, mine.step, mine.field.size(), mine.why.size()};
    MPI_Bcast(head, 5, MPI_UINT64_T, root, comm_);
    std::vector<char> text(std::size_t(head[3] + head[4]));
    if (rank_ == root) {
      mine.field.copy(text.data(), mine.field.size());
      mine.why.copy(text.data() + mine.field.size(), mine.why.size());
    }
    MPI_Bcast(text.data(), int(text.size()), MPI_CHAR, root, comm_);
    Failure f;
    f.kind = Kind(int(head[0]));
    f.body = std::size_t(head[1]), f.step = std::size_t(head[2]);
    f.field.assign(text.data(), std::size_t(head[3]));
    f.why.assign(text.data() + head[3], std::size_t(head[4]));
    return f;
  }

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
};

}  // namespace gpusolve::rbd
