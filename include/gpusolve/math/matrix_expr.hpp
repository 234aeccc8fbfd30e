// Operators on matrix expressions beyond the element-wise ones: matrix-vector
// and matrix-matrix products, transpose.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/elementwise.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/matrix3x3.hpp"
#include "gpusolve/math/node.hpp"
#include "gpusolve/math/vector3.hpp"

namespace gpusolve::math {
namespace op {

struct MatrixVector {
  static constexpr bool elementwise = false;
  template <class M, class V>
  GPUSOLVE_HD auto operator()(std::size_t i, const M& m, const V& v) const {
    return m[3 * i] * v[0] + m[3 * i + 1] * v[1] + m[3 * i + 2] * v[2];
  }
};

struct MatrixMatrix {
  static constexpr bool elementwise = false;
  template <class A, class B>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a, const B& b) const {
    const std::size_t r = 3 * (i / 3), c = i % 3;
    return a[r] * b[c] + a[r + 1] * b[3 + c] + a[r + 2] * b[6 + c];
  }
};

struct Transpose {
  static constexpr bool elementwise = false;
  template <class A>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a) const { return a[3 * (i % 3) + i / 3]; }
};

}  // namespace op

template <class M, class V, class T>
GPUSOLVE_HD auto operator*(const MatrixExpr<M, T>& m, const VectorExpr<V, T>& v) {
  return BinaryNode<VectorKind, op::MatrixVector, M, V>(m.derived(), v.derived());
}

template <class A, class B, class T>
GPUSOLVE_HD auto operator*(const MatrixExpr<A, T>& a, const MatrixExpr<B, T>& b) {
  return BinaryNode<MatrixKind, op::MatrixMatrix, A, B>(a.derived(), b.derived());
}

template <class A, class T>
GPUSOLVE_HD auto transpose(const MatrixExpr<A, T>& a) {
  return UnaryNode<MatrixKind, op::Transpose, A>(op::Transpose{}, a.derived());
}

}  // namespace gpusolve::math
