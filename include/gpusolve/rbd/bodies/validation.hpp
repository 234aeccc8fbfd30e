// InvalidBodyError and the checks that keep bad body input out of the solver.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <sstream>
#include <string>
#include <vector>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/bodies/body.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/parts.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

// A body's state (position, orientation or velocity) became NaN or infinite
// on the backend: found before a step changed anything, so that step was not
// taken and every body keeps the state it had. step() is the World's step
// count at that moment (npos when not known).
class NonFiniteStateError : public InvalidBodyError {
 public:
  static constexpr std::size_t npos = std::size_t(-1);
  NonFiniteStateError(std::size_t body, std::string field, std::size_t step = npos)
      : InvalidBodyError(body, std::move(field), why(step)), step_(step) {}
  std::size_t step() const noexcept { return step_; }

 private:
  static std::string why(std::size_t step) {
    std::ostringstream os;
    os << "is not finite";
    if (step != npos) os << " before step " << step << "; the step was not taken";
    return os.str();
  }
  std::size_t step_;
};

namespace detail {

// 4 * i + f for body i (not removed) whose state field f (pos, q, v, w) holds a
// NaN or infinity, else the largest key: the minimum over bodies names the first.
template <class BV>
struct NonFiniteKey {
  BV b;
  GPUSOLVE_HD std::uint64_t operator()(std::size_t i) const {
    using T = std::remove_cv_t<std::remove_reference_t<decltype(b.pos(i, 0))>>;
    if (b.status[i] == removed) return ~std::uint64_t(0);
    const auto bad = [](T x) { return !(x - x == T(0)); };  // NaN and inf give NaN
    for (std::size_t c = 0; c < 3; ++c)
      if (bad(b.pos(i, c))) return 4 * std::uint64_t(i);
    for (std::size_t c = 0; c < 4; ++c)
      if (bad(b.q(i, c))) return 4 * std::uint64_t(i) + 1;
    for (std::size_t c = 0; c < 3; ++c)
      if (bad(b.v(i, c))) return 4 * std::uint64_t(i) + 2;
    for (std::size_t c = 0; c < 3; ++c)
      if (bad(b.w(i, c))) return 4 * std::uint64_t(i) + 3;
    return ~std::uint64_t(0);
  }
};

// The error for a key of NonFiniteKey.
inline NonFiniteStateError non_finite_state(std::uint64_t key, std::size_t step = NonFiniteStateError::npos) {
  static const char* const fields[] = {"pos", "q", "v", "w"};
  return NonFiniteStateError(std::size_t(key / 4), fields[key % 4], step);
}

template <class T, std::size_t N>
void require_finite(const std::array<T, N>& a, std::size_t body, const char* field) {
  for (T x : a)
    if (!std::isfinite(x)) throw InvalidBodyError(body, field, "is not finite");
}

template <class T>
void require_unit(const std::array<T, 4>& q, std::size_t body, const std::string& field) {
  const T qq = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  if (std::abs(qq - T(1)) > T(1e-3)) throw InvalidBodyError(body, field, "is not a unit quaternion");
}

// The shape parameters p of a shape of body `index` (its ShapeTraits'
// validate), fields named after `prefix` (empty for the body itself,
// "parts[k]." for a compound's part).
template <class T>
void validate_shape(std::uint8_t shape, const std::array<T, shape_param_rows>& p, std::size_t index,
                    const std::string& prefix) {
  visit_kind<void>(
      shape, [&](auto k) { ShapeTraits<decltype(k)::value>::validate(p, index, prefix); },
      [&] { throw InvalidBodyError(index, prefix + "shape", "is not a ShapeKind"); });
}

}  // namespace detail

// Throws InvalidBodyError naming body `index` and the first offending field
// of part k (field "parts[k]. ..."): a sphere, box or capsule with valid
// parameters, a finite position and a unit orientation.
template <class T>
void validate_part(const Part<T>& part, std::size_t k, std::size_t index) {
  const std::string prefix = "parts[" + std::to_string(k) + "].";
  if (!part_kind(part.shape))
    throw InvalidBodyError(index, prefix + "shape", "must be a sphere, box or capsule (compounds do not nest)");
  detail::require_finite(part.shape_param, index, (prefix + "shape_param").c_str());
  detail::require_finite(part.pos, index, (prefix + "pos").c_str());
  detail::require_finite(part.q, index, (prefix + "q").c_str());
  detail::require_unit(part.q, index, prefix + "q");
  detail::validate_shape(part.shape, part.shape_param, index, prefix);
}

// Throws InvalidBodyError naming `index` and the first offending field. Checks:
// finite state; positive sphere radius, box half extents and capsule radius
// and half length; unit plane normal; a compound's 1 to max_parts parts (their
// own checks need the parts: the overload below); planes fixed; fixed bodies massless (0 inverse mass and inertia);
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
  if (b.status != active && b.status != fixed && b.status != removed && b.status != shadow)
    throw InvalidBodyError(index, "status", "is not a BodyStatus");
  detail::require_unit(b.q, index, "q");
  detail::validate_shape(b.shape, b.shape_param, index, "");
  const bool moving = moves(b.status);
  if (moving && !visit_kind<bool>(
                    b.shape, [](auto k) { return ShapeTraits<decltype(k)::value>::moves; }, [] { return false; }))
    throw InvalidBodyError(index, "status", std::string(shape_name(b.shape)) + "s must be fixed");
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

// validate_body, and for a compound its parts among `parts` (a BodySet's):
// the range [first_part, first_part + count) must lie in it.
template <class T>
void validate_body(const Body<T>& b, std::size_t index, const std::vector<Part<T>>& parts) {
  validate_body(b, index);
  if (b.shape != compound) return;
  const std::size_t count = std::size_t(b.shape_param[0]);
  if (b.first_part > parts.size() || count > parts.size() - b.first_part)
    throw InvalidBodyError(index, "first_part", "its parts lie past the end of the BodySet's parts");
  for (std::size_t k = 0; k < count; ++k) validate_part(parts[b.first_part + k], k, index);
}

}  // namespace gpusolve::rbd
