// Vector3 and the operators every kind shares, against double-precision references.
#include <cmath>
#include <random>
#include <type_traits>

#include "catch_compat.hpp"
#include "gpusolve/math.hpp"
#include "test_math_support.hpp"

using namespace gpusolve::math;
using namespace math_test;

TEMPLATE_TEST_CASE("vector operators match a double reference", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(11);
  for (int n = 0; n < repeats; ++n) {
    const Vector3<T> a = random_vector<T>(rng), b = random_vector<T>(rng), c = random_vector<T>(rng);
    const T s = uniform<T>(rng, 0.5, 2);
    const R3 ra = ref(a), rb = ref(b), rc = ref(c);

    require_close(Vector3<T>(a + b), lin(1, ra, 1, rb));
    require_close(Vector3<T>(a - b), lin(1, ra, -1, rb));
    require_close(Vector3<T>(-a), lin(-1, ra, 0, rb));
    require_close(Vector3<T>(a * s), lin(s, ra, 0, rb));
    require_close(Vector3<T>(s * a), lin(s, ra, 0, rb));
    require_close(Vector3<T>(a / s), lin(1 / double(s), ra, 0, rb));
    require_close(Vector3<T>(a % b), cross(ra, rb));
    // the thesis's gap-function term: p + v dt + r - (r x w) dt
    require_close(Vector3<T>(a + b * s + c - (c % a) * s),
                  lin(1, lin(1, ra, s, rb), 1, lin(1, rc, -double(s), cross(rc, ra))));

    require_close_scalar(dot(a, b), dot(ra, rb), tol<T>());
    require_close_scalar(sqr_norm(a), dot(ra, ra), tol<T>());
    require_close_scalar(norm(a - b), std::sqrt(dot(lin(1, ra, -1, rb), lin(1, ra, -1, rb))), tol<T>());
    const double na = std::sqrt(dot(ra, ra));
    require_close(Vector3<T>(normalize(a)), lin(1 / na, ra, 0, rb));
  }
}

TEMPLATE_TEST_CASE("vector compound assignments", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(12);
  for (int n = 0; n < repeats; ++n) {
    Vector3<T> a = random_vector<T>(rng);
    const Vector3<T> b = random_vector<T>(rng);
    const T s = uniform<T>(rng, 0.5, 2);
    R3 r = ref(a);
    a += b;   r = lin(1, r, 1, ref(b));   require_close(a, r);
    a -= b * s; r = lin(1, r, -double(s), ref(b)); require_close(a, r);
    a *= s;   r = lin(s, r, 0, r);        require_close(a, r);
    a /= s;   r = lin(1 / double(s), r, 0, r); require_close(a, r);
    a += a;   r = lin(2, r, 0, r);        require_close(a, r);
  }
}

TEMPLATE_TEST_CASE("vector assignments that read their target", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(13);
  for (int n = 0; n < repeats; ++n) {
    Vector3<T> a = random_vector<T>(rng);
    const Vector3<T> b = random_vector<T>(rng), c = random_vector<T>(rng);
    R3 r = ref(a);
    a = b % a;          r = cross(ref(b), r);                   require_close(a, r);
    a = a % b;          r = cross(r, ref(b));                   require_close(a, r);
    a = c + a % (b - a); r = lin(1, ref(c), 1, cross(r, lin(1, ref(b), -1, r))); require_close(a, r);
    a = a - b;          r = lin(1, r, -1, ref(b));              require_close(a, r);
    a = normalize(a);   r = lin(1 / std::sqrt(dot(r, r)), r, 0, r); require_close(a, r);
  }
}

TEST_CASE("normalize leaves a zero vector unchanged", "[math]") {
  const Vector3<double> z;
  const Vector3<double> n = normalize(z);
  CHECK(n[0] == 0);
  CHECK(n[1] == 0);
  CHECK(n[2] == 0);
}

TEST_CASE("value types start at zero and take their elements in order", "[math]") {
  const Vector3<float> z;
  CHECK((z[0] == 0 && z[1] == 0 && z[2] == 0));
  const Vector3<float> v(1, 2, 3);
  CHECK((v[0] == 1 && v[1] == 2 && v[2] == 3));
}

TEST_CASE("operands are held by reference for value types, by copy otherwise", "[math]") {
  using V = Vector3<float>;
  using G = Vector3Global<float>;
  using Sum = decltype(std::declval<V>() + std::declval<V>());
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<V>, const V&>);
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<Matrix3x3<double>>, const Matrix3x3<double>&>);
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<Quaternion<float>>, const Quaternion<float>&>);
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<G>, G>);
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<QuaternionGlobal<double>>, QuaternionGlobal<double>>);
  STATIC_REQUIRE(std::is_same_v<expr_storage_t<Sum>, Sum>);
}

TEST_CASE("only expressions that read other elements need a temporary", "[math]") {
  using V = Vector3<float>;
  using M = Matrix3x3<float>;
  using Q = Quaternion<float>;
  const V a, b;
  const M m;
  const Q q;
  STATIC_REQUIRE_FALSE(decltype(a + b * 2.0f - (-a) / 3.0f)::needs_temporary);
  STATIC_REQUIRE_FALSE(decltype(conj(q) + q)::needs_temporary);
  STATIC_REQUIRE(decltype(a % b)::needs_temporary);
  STATIC_REQUIRE(decltype(a + 2.0f * (a % b))::needs_temporary);  // propagates upward
  STATIC_REQUIRE(decltype(m * a)::needs_temporary);
  STATIC_REQUIRE(decltype(m * m)::needs_temporary);
  STATIC_REQUIRE(decltype(transpose(m))::needs_temporary);
  STATIC_REQUIRE(decltype(q * q)::needs_temporary);
}
