// Shared by the math tests: random inputs and double-precision references
// written independently of gpusolve::math (plain arrays, textbook formulas).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <random>

#include "catch_compat.hpp"
#include "gpusolve/math.hpp"

namespace math_test {

template <std::size_t N> using Ref = std::array<double, N>;
using R3 = Ref<3>;
using R4 = Ref<4>;
using R9 = Ref<9>;

// Relative tolerance of a result made of a few roundings of inputs in [-1, 1].
template <class T> constexpr double tol() { return sizeof(T) == sizeof(float) ? 2e-5 : 1e-12; }

template <class E, class K, class T>
Ref<K::size> ref(const gpusolve::math::Expr<E, K, T>& e) {
  Ref<K::size> r{};
  for (std::size_t i = 0; i < K::size; ++i) r[i] = static_cast<double>(e.derived()[i]);
  return r;
}

// Every element of e matches the reference r.
template <class T, class E, class K, std::size_t N>
void require_close(const gpusolve::math::Expr<E, K, T>& e, const Ref<N>& r) {
  static_assert(K::size == N);
  for (std::size_t i = 0; i < N; ++i) {
    INFO("element " << i << ": got " << e.derived()[i] << ", expected " << r[i]);
    CHECK(std::abs(e.derived()[i] - r[i]) <= tol<T>() * (1 + std::abs(r[i])));
  }
}

inline void require_close_scalar(double got, double expected, double t) {
  INFO("got " << got << ", expected " << expected);
  CHECK(std::abs(got - expected) <= t * (1 + std::abs(expected)));
}

// --- references -------------------------------------------------------------
template <std::size_t N> Ref<N> lin(double a, const Ref<N>& x, double b, const Ref<N>& y) {
  Ref<N> r{};
  for (std::size_t i = 0; i < N; ++i) r[i] = a * x[i] + b * y[i];
  return r;
}
template <std::size_t N> double dot(const Ref<N>& a, const Ref<N>& b) {
  double s = 0;
  for (std::size_t i = 0; i < N; ++i) s += a[i] * b[i];
  return s;
}
inline R3 cross(const R3& a, const R3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double at(const R9& m, int r, int c) { return m[3 * r + c]; }
inline R3 matvec(const R9& m, const R3& v) {
  R3 r{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i] += at(m, i, k) * v[k];
  return r;
}
inline R9 matmul(const R9& a, const R9& b) {
  R9 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[3 * i + j] += at(a, i, k) * at(b, k, j);
  return r;
}
inline R9 transpose(const R9& m) {
  R9 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[3 * i + j] = at(m, j, i);
  return r;
}
// Quaternion product in scalar-vector form: (a0 b0 - a.b, a0 b + b0 a + a x b).
inline R4 qmul(const R4& a, const R4& b) {
  const R3 u{a[1], a[2], a[3]}, v{b[1], b[2], b[3]};
  const R3 x = lin(a[0], v, b[0], u), c = cross(u, v);
  return {a[0] * b[0] - dot(u, v), x[0] + c[0], x[1] + c[1], x[2] + c[2]};
}
// q v q* through two quaternion products.
inline R3 qrotate(const R4& q, const R3& v) {
  const R4 r = qmul(qmul(q, {0, v[0], v[1], v[2]}), {q[0], -q[1], -q[2], -q[3]});
  return {r[1], r[2], r[3]};
}
// The matrix whose columns are the rotated basis vectors.
inline R9 qmatrix(const R4& q) {
  R9 m{};
  for (int c = 0; c < 3; ++c) {
    R3 e{};
    e[c] = 1;
    const R3 col = qrotate(q, e);
    for (int r = 0; r < 3; ++r) m[3 * r + c] = col[r];
  }
  return m;
}
// Rodrigues: the rotation by `angle` about the unit vector `k`.
inline R9 rodrigues(const R3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  R9 m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m[3 * i + j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
  m[1] -= s * k[2]; m[2] += s * k[1];
  m[3] += s * k[2]; m[5] -= s * k[0];
  m[6] -= s * k[1]; m[7] += s * k[0];
  return m;
}

// --- random inputs ----------------------------------------------------------
template <class T> T uniform(std::mt19937& rng, double lo = -1, double hi = 1) {
  return static_cast<T>(std::uniform_real_distribution<double>(lo, hi)(rng));
}
template <class T> gpusolve::math::Vector3<T> random_vector(std::mt19937& rng) {
  return {uniform<T>(rng), uniform<T>(rng), uniform<T>(rng)};
}
template <class T> gpusolve::math::Matrix3x3<T> random_matrix(std::mt19937& rng) {
  gpusolve::math::Matrix3x3<T> m;
  for (std::size_t i = 0; i < 9; ++i) m[i] = uniform<T>(rng);
  return m;
}
// A A^T + I: symmetric, eigenvalues in [1, 10].
template <class T> gpusolve::math::Matrix3x3<T> random_spd(std::mt19937& rng) {
  const R9 a = ref(random_matrix<T>(rng)), s = matmul(a, transpose(a));
  gpusolve::math::Matrix3x3<T> m;
  for (std::size_t i = 0; i < 9; ++i) m[i] = static_cast<T>(s[i] + (i % 4 == 0 ? 1 : 0));
  return m;
}
template <class T> gpusolve::math::Quaternion<T> random_unit_quaternion(std::mt19937& rng) {
  R4 q{};
  do {
    for (double& x : q) x = uniform<double>(rng);
  } while (dot(q, q) < 0.01);
  const double n = std::sqrt(dot(q, q));
  return {T(q[0] / n), T(q[1] / n), T(q[2] / n), T(q[3] / n)};
}

inline constexpr int repeats = 200;

}  // namespace math_test
