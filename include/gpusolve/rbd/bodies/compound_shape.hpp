// The compound (pe's Union): one rigid body made of sphere, box and capsule
// parts (parts.hpp). Parameters (number of parts, bounding radius, smallest
// feature size, 0), set by BodySet::add_compound_type from the parts, which
// are Bodies::parts [first_part, first_part + number).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/invalid_body_error.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"

namespace gpusolve::rbd {

// A compound holds at most this many parts: a contact's feature id keeps 8
// bits for the part of each body (collision/body_manifolds.hpp).
inline constexpr std::size_t max_parts = 256;

template <>
struct ShapeTraits<compound> {
  static constexpr const char* name = "compound";
  static constexpr std::size_t params = 3;
  static constexpr bool rotated = true;
  static constexpr bool part = false;  // compounds do not nest
  static constexpr bool moves = true;

  template <class T>
  GPUSOLVE_HD static T bound(T, T bound, T) {
    return bound;
  }
  template <class T>
  GPUSOLVE_HD static T feature(T, T, T smallest) {
    return smallest;
  }
  // The record's own slots; its parts are checked against the BodySet's
  // (validation.hpp's validate_body).
  template <class T>
  static void validate(const std::array<T, shape_param_rows>& p, std::size_t body, const std::string& prefix) {
    const T count = p[0];
    if (!(count >= 1) || count > T(max_parts) || count != T(std::size_t(count)))
      throw InvalidBodyError(body, prefix + "parts", "a compound has 1 to 256 parts");
    if (!(p[1] > 0) || !(p[2] > 0))
      throw InvalidBodyError(body, prefix + "shape_param",
                             "a compound's bounds come from its parts (BodySet::add_compound_type)");
  }
};

}  // namespace gpusolve::rbd
