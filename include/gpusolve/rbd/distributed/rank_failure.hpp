// RankFailure: what one rank threw, as data that travels to the other ranks,
// and the same error thrown again wherever it arrives.
#pragma once

#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"

namespace gpusolve::rbd {

// An error that another rank threw, of none of the library's own types (those
// are thrown again as their own type): its rank and message.
class RankFailedError : public Error {
 public:
  RankFailedError(int rank, const std::string& what)
      : Error("gpusolve: rank " + std::to_string(rank) + ": " + what), rank_(rank) {}
  int rank() const noexcept { return rank_; }

 private:
  int rank_;
};

struct RankFailure {
  enum class Kind : std::uint64_t { none, non_finite, invalid_body, out_of_memory, unsupported, invalid_argument, other };
  Kind kind = Kind::none;
  std::uint64_t body = 0, step = 0, bytes = 0;
  std::string field, why;

  // The exception being handled (call it inside a catch block).
  static RankFailure current() {
    try {
      throw;
    } catch (const NonFiniteStateError& e) {
      return {Kind::non_finite, e.body(), e.step(), 0, e.field(), reason(e)};
    } catch (const InvalidBodyError& e) {
      return {Kind::invalid_body, e.body(), 0, 0, e.field(), reason(e)};
    } catch (const OutOfMemoryError& e) {
      return {Kind::out_of_memory, 0, 0, e.requested_bytes(), "", e.what()};
    } catch (const UnsupportedError& e) {
      return {Kind::unsupported, 0, 0, 0, "", e.what()};
    } catch (const InvalidArgumentError& e) {
      return {Kind::invalid_argument, 0, 0, 0, "", e.what()};
    } catch (const std::exception& e) {
      return {Kind::other, 0, 0, 0, "", e.what()};
    } catch (...) {
      return {Kind::other, 0, 0, 0, "", "an exception that is not a std::exception"};
    }
  }

  // Throws it as rank `rank`'s failure: a NonFiniteStateError or
  // InvalidBodyError with the same body, field and step; an OutOfMemoryError
  // (of the same bytes), UnsupportedError or InvalidArgumentError whose
  // message names the rank; else a RankFailedError.
  [[noreturn]] void throw_from(int rank) const {
    const std::string named = "gpusolve: rank " + std::to_string(rank) + ": " + why;
    if (kind == Kind::non_finite) throw NonFiniteStateError(body, field, step);
    if (kind == Kind::invalid_body) throw InvalidBodyError(body, field, why);
    if (kind == Kind::out_of_memory) throw OutOfMemoryError(bytes, named);
    if (kind == Kind::unsupported) throw UnsupportedError(named);
    if (kind == Kind::invalid_argument) throw InvalidArgumentError(named);
    throw RankFailedError(rank, why);
  }

  // As bytes (six numbers, then the field and the reason) and back.
  std::vector<char> pack() const {
    const std::uint64_t head[6] = {std::uint64_t(kind), body, step, bytes, field.size(), why.size()};
    std::vector<char> out(sizeof head + field.size() + why.size());
    std::memcpy(out.data(), head, sizeof head);
    field.copy(out.data() + sizeof head, field.size());
    why.copy(out.data() + sizeof head + field.size(), why.size());
    return out;
  }
  static RankFailure unpack(const std::vector<char>& in) {
    std::uint64_t head[6];
    std::memcpy(head, in.data(), sizeof head);
    RankFailure f;
    f.kind = Kind(head[0]), f.body = head[1], f.step = head[2], f.bytes = head[3];
    f.field.assign(in.data() + sizeof head, std::size_t(head[4]));
    f.why.assign(in.data() + sizeof head + head[4], std::size_t(head[5]));
    return f;
  }

 private:
  // An InvalidBodyError's reason, without the "body N, field `f`: " its message starts with.
  static std::string reason(const InvalidBodyError& e) {
    const std::string w = e.what();
    const std::size_t p = w.find("`: ");
    return p == std::string::npos ? w : w.substr(p + 3);
  }
};

}  // namespace gpusolve::rbd
