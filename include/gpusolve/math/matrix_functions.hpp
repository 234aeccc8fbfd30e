// Matrix functions evaluated at once into a value: the inverse of a symmetric
// positive definite matrix and the rotated tensor R I R^T.
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/matrix3x3.hpp"
#include "gpusolve/math/matrix_expr.hpp"

namespace gpusolve::math {

// Inverse of a symmetric positive definite matrix (an inertia tensor, a
// contact's diagonal block) from its upper triangle, by cofactors. A singular
// input yields inf/NaN, never a plausible-looking matrix.
template <class M, class T>
GPUSOLVE_HD Matrix3x3<T> inverse_spd(const MatrixExpr<M, T>& m) {
  const M& s = m.derived();
  const T a = s[0], b = s[1], c = s[2], d = s[4], e = s[5], f = s[8];  // [a b c; b d e; c e f]
  const T c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const T c11 = a * f - c * c, c12 = b * c - a * e, c22 = a * d - b * b;
  const T inv_det = T(1) / (a * c00 + b * c01 + c * c02);
  return Matrix3x3<T>(c00, c01, c02, c01, c11, c12, c02, c12, c22) * inv_det;
}

// R I R^T: a body-frame tensor I expressed in the frame that R rotates into.
template <class R, class I, class T>
GPUSOLVE_HD Matrix3x3<T> rotate_tensor(const MatrixExpr<R, T>& rotation, const MatrixExpr<I, T>& tensor) {
  const Matrix3x3<T> r(rotation), ri = r * tensor;
  return ri * transpose(r);
}

}  // namespace gpusolve::math
