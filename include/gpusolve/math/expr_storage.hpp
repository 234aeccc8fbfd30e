// How an expression node holds its operands (thesis Listing 5).
#pragma once

#include <type_traits>

#include "gpusolve/math/expr.hpp"

namespace gpusolve::math {

// Value types (Vector3, Matrix3x3, Quaternion) by const reference: copying
// their elements into every node bloated nvcc's code. Global types and nested
// expressions by copy: they are small handles, and nvcc only optimises them
// away when held by value. The caveat of every expression-template library
// follows: an expression must be evaluated in the statement that builds it,
// never kept in an `auto` variable past it.
template <class E>
using expr_storage_t = std::conditional_t<std::is_same_v<E, value_t<E>>, const E&, E>;

}  // namespace gpusolve::math
