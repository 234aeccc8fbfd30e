// Operators on vector expressions beyond the element-wise ones: the cross product.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/elementwise.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/node.hpp"
#include "gpusolve/math/vector3.hpp"

namespace gpusolve::math {
namespace op {

struct Cross {
  static constexpr bool elementwise = false;
  template <class A, class B>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a, const B& b) const {
    const std::size_t j = (i + 1) % 3, k = (i + 2) % 3;
    return a[j] * b[k] - a[k] * b[j];
  }
};

}  // namespace op

// a x b (pe's spelling).
template <class A, class B, class T>
GPUSOLVE_HD auto operator%(const VectorExpr<A, T>& a, const VectorExpr<B, T>& b) {
  return BinaryNode<VectorKind, op::Cross, A, B>(a.derived(), b.derived());
}

}  // namespace gpusolve::math
