// InvalidBodyError and the checks that keep bad body input out of the solver.
#pragma once

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/bodies/body.hpp"

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

namespace detail {

template <class T, std::size_t N>
void require_finite(const std::array<T, N>& a, std::size_t body, const char* field) {
  for (T x : a)
    if (!std::isfinite(x)) throw InvalidBodyError(body, field, "is not finite");
}

}  // namespace detail

// Throws InvalidBodyError naming `index` and the first offending field. Checks:
// finite state; positive sphere radius and box half extents; unit plane normal;
// boxes and planes fixed; fixed bodies massless (0 inverse mass and inertia);
// moving bodies with a positive finite mass and a positive inertia diagonal.
template <class T>
void validate_body(const Body<T>& b, std::size_t index) {
  using detail::require_finite;
  require_finite(b.pos, index, "pos");
  require_finite(b.q, index, "q");
  require_finite(b.v, index, "v");
  require_finite(b.w, index, "w");
  require_finite(b.force, index, "force");
  require_finite(b.torque, index, "torque");
  require_finite(b.shape_param, index, "shape_param");
  require_finite(b.inertia, index, "inertia");
  require_finite(b.inv_inertia_body, index, "inv_inertia_body");
  if (b.status != active && b.status != fixed && b.status != removed)
    throw InvalidBodyError(index, "status", "is not a BodyStatus");
  const T qq = b.q[0] * b.q[0] + b.q[1] * b.q[1] + b.q[2] * b.q[2] + b.q[3] * b.q[3];
  if (std::abs(qq - T(1)) > T(1e-3)) throw InvalidBodyError(index, "q", "is not a unit quaternion");
  const auto& p = b.shape_param;
  switch (b.shape) {
    case sphere:
      if (!(p[0] > 0)) throw InvalidBodyError(index, "radius", "must be positive");
      break;
    case box:
      for (int k = 0; k < 3; ++k)
        if (!(p[k] > 0)) throw InvalidBodyError(index, "half_extents", "must be positive");
      break;
    case plane: {
      const T nn = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
      if (std::abs(nn - T(1)) > T(1e-4)) throw InvalidBodyError(index, "normal", "must have unit length");
      break;
    }
    default:
      throw InvalidBodyError(index, "shape", "is not a ShapeKind");
  }
  const bool moving = b.status == active;
  if (b.shape != sphere && moving)
    throw InvalidBodyError(index, "status", "boxes and planes must be fixed");
  if (!std::isfinite(b.inv_mass) || b.inv_mass < 0)
    throw InvalidBodyError(index, "mass", "must be positive and finite");
  if (moving) {
    if (!(b.inv_mass > 0)) throw InvalidBodyError(index, "mass", "must be positive and finite");
    for (int k = 0; k < 3; ++k)
      if (!(b.inertia[4 * k] > 0) || !(b.inv_inertia_body[4 * k] > 0))
        throw InvalidBodyError(index, "inertia", "diagonal must be positive");
  } else if (b.status == fixed) {
    if (b.inv_mass != 0) throw InvalidBodyError(index, "mass", "fixed bodies have inverse mass 0");
    for (T x : b.inv_inertia_body)
      if (x != 0) throw InvalidBodyError(index, "inertia", "fixed bodies have inverse inertia 0");
  }
}

}  // namespace gpusolve::rbd
