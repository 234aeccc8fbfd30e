// Element-wise operators shared by every kind: +, -, unary -, scalar * and /,
// and the compound assignments built on them.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/node.hpp"

namespace gpusolve::math {
namespace op {

struct Plus {
  static constexpr bool elementwise = true;
  template <class A, class B>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a, const B& b) const { return a[i] + b[i]; }
};

struct Minus {
  static constexpr bool elementwise = true;
  template <class A, class B>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a, const B& b) const { return a[i] - b[i]; }
};

struct Negate {
  static constexpr bool elementwise = true;
  template <class A>
  GPUSOLVE_HD auto operator()(std::size_t i, const A& a) const { return -a[i]; }
};

template <class T>
struct Times {
  static constexpr bool elementwise = true;
  T s;
  template <class A>
  GPUSOLVE_HD T operator()(std::size_t i, const A& a) const { return a[i] * s; }
};

template <class T>
struct DividedBy {
  static constexpr bool elementwise = true;
  T s;
  template <class A>
  GPUSOLVE_HD T operator()(std::size_t i, const A& a) const { return a[i] / s; }
};

}  // namespace op

template <class A, class B, class K, class T>
GPUSOLVE_HD auto operator+(const Expr<A, K, T>& a, const Expr<B, K, T>& b) {
  return BinaryNode<K, op::Plus, A, B>(a.derived(), b.derived());
}

template <class A, class B, class K, class T>
GPUSOLVE_HD auto operator-(const Expr<A, K, T>& a, const Expr<B, K, T>& b) {
  return BinaryNode<K, op::Minus, A, B>(a.derived(), b.derived());
}

template <class A, class K, class T>
GPUSOLVE_HD auto operator-(const Expr<A, K, T>& a) {
  return UnaryNode<K, op::Negate, A>(op::Negate{}, a.derived());
}

template <class A, class K, class T>
GPUSOLVE_HD auto operator*(const Expr<A, K, T>& a, detail::type_identity_t<T> s) {
  return UnaryNode<K, op::Times<T>, A>(op::Times<T>{s}, a.derived());
}

template <class A, class K, class T>
GPUSOLVE_HD auto operator*(detail::type_identity_t<T> s, const Expr<A, K, T>& a) {
  return a * s;
}

template <class A, class K, class T>
GPUSOLVE_HD auto operator/(const Expr<A, K, T>& a, detail::type_identity_t<T> s) {
  return UnaryNode<K, op::DividedBy<T>, A>(op::DividedBy<T>{s}, a.derived());
}

// d op= e is d = d op e: element-wise, so safe even when e reads d. They apply
// to value and Global types; an expression node has no assignment to call.
template <class D, class E, class K, class T>
GPUSOLVE_HD D& operator+=(Expr<D, K, T>& d, const Expr<E, K, T>& e) {
  return d.derived() = d.derived() + e.derived();
}

template <class D, class E, class K, class T>
GPUSOLVE_HD D& operator-=(Expr<D, K, T>& d, const Expr<E, K, T>& e) {
  return d.derived() = d.derived() - e.derived();
}

template <class D, class K, class T>
GPUSOLVE_HD D& operator*=(Expr<D, K, T>& d, detail::type_identity_t<T> s) {
  return d.derived() = d.derived() * s;
}

template <class D, class K, class T>
GPUSOLVE_HD D& operator/=(Expr<D, K, T>& d, detail::type_identity_t<T> s) {
  return d.derived() = d.derived() / s;
}

}  // namespace gpusolve::math
