// InvalidBodyError: a body's field holds what the solver cannot work with.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <utility>

#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd {

// A body's field holds a value the solver cannot work with; names both.
class InvalidBodyError : public InvalidArgumentError {
 public:
  InvalidBodyError(std::size_t body, std::string field, const std::string& why)
      : InvalidArgumentError(message(body, field, why)), body_(body), field_(std::move(field)) {}
  std::size_t body() const noexcept { return body_; }
  const std::string& field() const noexcept { return field_; }

 private:
  static std::string message(std::size_t body, const std::string& field, const std::string& why) {
    std::ostringstream os;
    os << "gpusolve: body " << body << ", field `" << field << "`: " << why;
    return os.str();
  }
  std::size_t body_;
  std::string field_;
};

}  // namespace gpusolve::rbd
