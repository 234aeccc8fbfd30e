// Inner product and the norms built on it, for every kind; normalisation.
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/elementwise.hpp"
#include "gpusolve/math/expr.hpp"

namespace gpusolve::math {

// Sum of a[i] * b[i]: the dot product of vectors (and of quaternions seen as 4-vectors).
template <class A, class B, class K, class T>
GPUSOLVE_HD T dot(const Expr<A, K, T>& a, const Expr<B, K, T>& b) {
  T s = 0;
  for (std::size_t i = 0; i < K::size; ++i) s += a.derived()[i] * b.derived()[i];
  return s;
}

template <class A, class K, class T>
GPUSOLVE_HD T sqr_norm(const Expr<A, K, T>& a) {
  T s = 0;
  for (std::size_t i = 0; i < K::size; ++i) {
    const T x = a.derived()[i];  // read once: a may be an expression or global memory
    s += x * x;
  }
  return s;
}

template <class A, class K, class T>
GPUSOLVE_HD T norm(const Expr<A, K, T>& a) {
  return std::sqrt(sqr_norm(a));
}

// a / |a| as an element-wise expression; the norm is computed here, before any
// element is written, so `a = normalize(a)` is safe. A zero vector has no
// direction: it comes back unchanged rather than as NaN.
template <class A, class K, class T>
GPUSOLVE_HD auto normalize(const Expr<A, K, T>& a) {
  const T n = norm(a);
  return a * (n > T(0) ? T(1) / n : T(1));
}

}  // namespace gpusolve::math
