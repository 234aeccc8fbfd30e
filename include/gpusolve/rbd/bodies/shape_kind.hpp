// ShapeKind: pe's primitives (thesis 3.1) and its Union, here `compound`, and
// the traits each kind declares in a header of its own (sphere_shape.hpp, ...).
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace gpusolve::rbd {

enum ShapeKind : std::uint8_t { sphere = 0, box = 1, plane = 2, capsule = 3, compound = 4 };
inline constexpr int shape_kinds = 5;

// Every body and part holds this many shape parameters (rows of
// Bodies::shape_param); each kind's header says what its slots mean.
inline constexpr std::size_t shape_param_rows = 4;

// A kind's facts, one specialisation per kind in its own header: name,
// params (the slots it reads), rotated (whether its surface turns with the
// body), part (whether a compound may hold it), moves (whether it may be a
// moving body), bound and feature (from its parameters), validate, and solid
// (mass properties) for the kinds a body or part can be made of alone. A kind
// without its traits is an incomplete type: code that visits it does not compile.
template <ShapeKind K>
struct ShapeTraits;

// A kind as a type, for visiting (shapes.hpp's visit_kind).
template <ShapeKind K>
using KindConstant = std::integral_constant<ShapeKind, K>;

}  // namespace gpusolve::rbd
