// The CRTP base of every math expression, the three kinds of object, and the
// assignment that evaluates an expression element by element (thesis 4.2.1).
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::math {

template <class T> class Vector3;
template <class T> class Matrix3x3;
template <class T> class Quaternion;

// What an expression evaluates to: its number of elements and its value type.
// Matrices are stored row-major (element (r, c) is element 3r + c), quaternions
// as (w, x, y, z).
struct VectorKind {
  static constexpr std::size_t size = 3;
  template <class T> using value = Vector3<T>;
};
struct MatrixKind {
  static constexpr std::size_t size = 9;
  template <class T> using value = Matrix3x3<T>;
};
struct QuaternionKind {
  static constexpr std::size_t size = 4;
  template <class T> using value = Quaternion<T>;
};

// Base of value types, Global types and expression nodes. Every derived class
// E provides `T operator[](std::size_t) const` and `static constexpr bool
// needs_temporary`: true when computing element i reads elements other than i
// of some operand (cross, products, transpose). Such an expression cannot be
// written element by element into one of its own operands (`a = b % a` would
// read a[0] after overwriting it), so assign() evaluates it into a value first.
template <class E, class Kind, class T>
struct Expr {
  using kind = Kind;
  using scalar = T;
  static constexpr std::size_t size = Kind::size;

  GPUSOLVE_HD const E& derived() const { return static_cast<const E&>(*this); }
  GPUSOLVE_HD E& derived() { return static_cast<E&>(*this); }
};

template <class E, class T> using VectorExpr = Expr<E, VectorKind, T>;
template <class E, class T> using MatrixExpr = Expr<E, MatrixKind, T>;
template <class E, class T> using QuaternionExpr = Expr<E, QuaternionKind, T>;

// The value type an expression evaluates to (Vector3<T>, Matrix3x3<T>, Quaternion<T>).
template <class E>
using value_t = typename E::kind::template value<typename E::scalar>;

namespace detail {

// Keeps a scalar parameter out of template deduction, so `2 * v` works for Vector3<float>.
template <class T> struct type_identity { using type = T; };
template <class T> using type_identity_t = typename type_identity<T>::type;

template <class Dst, class E>
GPUSOLVE_HD void copy_elements(Dst& dst, const E& e) {
  for (std::size_t i = 0; i < E::size; ++i) dst[i] = e[i];
}

}  // namespace detail

// dst = e, safe when e reads dst (see needs_temporary above). Element-wise
// expressions are written straight through, one element at a time: the
// register saving of thesis Table 4.
template <class Dst, class E>
GPUSOLVE_HD void assign(Dst& dst, const E& e) {
  if constexpr (E::needs_temporary) {
    const value_t<E> tmp(e);
    detail::copy_elements(dst, tmp);
  } else {
    detail::copy_elements(dst, e);
  }
}

}  // namespace gpusolve::math
