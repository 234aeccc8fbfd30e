// Operators on quaternion expressions beyond the element-wise ones: the
// Hamilton product and the conjugate.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/elementwise.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/node.hpp"
#include "gpusolve/math/quaternion.hpp"

namespace gpusolve::math {
namespace op {

struct HamiltonProduct {
  static constexpr bool elementwise = false;
  template <class A, class B>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a, const B& b) const {
    switch (i) {
      case 0: return a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
      case 1: return a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
      case 2: return a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
      default: return a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    }
  }
};

struct Conjugate {
  static constexpr bool elementwise = true;
  template <class A>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a) const { return i == 0 ? a[0] : -a[i]; }
};

}  // namespace op

// a * b: the rotation b followed by the rotation a.
template <class A, class B, class T>
GPUSOLVE_HD auto operator*(const QuaternionExpr<A, T>& a, const QuaternionExpr<B, T>& b) {
  return BinaryNode<QuaternionKind, op::HamiltonProduct, A, B>(a.derived(), b.derived());
}

// (w, -x, -y, -z): the inverse rotation of a unit quaternion.
template <class A, class T>
GPUSOLVE_HD auto conj(const QuaternionExpr<A, T>& a) {
  return UnaryNode<QuaternionKind, op::Conjugate, A>(op::Conjugate{}, a.derived());
}

}  // namespace gpusolve::math
