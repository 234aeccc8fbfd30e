// Matrix3x3 operators and matrix functions against double-precision references.
#include <random>

#include "catch_compat.hpp"
#include "gpusolve/math.hpp"
#include "test_math_support.hpp"

using namespace gpusolve::math;
using namespace math_test;

TEMPLATE_TEST_CASE("matrix operators match a double reference", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(21);
  for (int n = 0; n < repeats; ++n) {
    const Matrix3x3<T> a = random_matrix<T>(rng), b = random_matrix<T>(rng);
    const Vector3<T> v = random_vector<T>(rng);
    const T s = uniform<T>(rng, 0.5, 2);
    const R9 ra = ref(a), rb = ref(b);

    require_close(Matrix3x3<T>(a + b), lin(1, ra, 1, rb));
    require_close(Matrix3x3<T>(a - s * b), lin(1, ra, -double(s), rb));
    require_close(Matrix3x3<T>(-a / s), lin(-1 / double(s), ra, 0, rb));
    require_close(Vector3<T>(a * v), matvec(ra, ref(v)));
    require_close(Matrix3x3<T>(a * b), matmul(ra, rb));
    require_close(Matrix3x3<T>(transpose(a)), transpose(ra));
    require_close(Matrix3x3<T>(a * transpose(b) + b), lin(1, matmul(ra, transpose(rb)), 1, rb));
    require_close(Vector3<T>(transpose(a) * (b * v)), matvec(transpose(ra), matvec(rb, ref(v))));
    CHECK(a(1, 2) == a[5]);
  }
}

TEMPLATE_TEST_CASE("matrix assignments that read their target", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(22);
  for (int n = 0; n < repeats; ++n) {
    Matrix3x3<T> m = random_matrix<T>(rng);
    const Matrix3x3<T> b = random_matrix<T>(rng);
    Vector3<T> v = random_vector<T>(rng);
    R9 r = ref(m);
    R3 rv = ref(v);
    v = m * v;            rv = matvec(r, rv);           require_close(v, rv);
    m = m * b;            r = matmul(r, ref(b));        require_close(m, r);
    m = b * m;            r = matmul(ref(b), r);        require_close(m, r);
    m = transpose(m);     r = transpose(r);             require_close(m, r);
    m = m * m;            r = matmul(r, r);             require_close(m, r);
    m += transpose(m);    r = lin(1, r, 1, transpose(r)); require_close(m, r);
    m *= T(0.25);         r = lin(0.25, r, 0, r);       require_close(m, r);
  }
}

TEMPLATE_TEST_CASE("inverse of a symmetric positive definite matrix", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(23);
  for (int n = 0; n < repeats; ++n) {
    const Matrix3x3<T> m = random_spd<T>(rng);
    const Matrix3x3<T> inv = inverse_spd(m);
    // m * inv = I, with the product taken in double
    require_close(Matrix3x3<T>(Matrix3x3<T>::identity()), matmul(ref(m), ref(inv)));
    require_close(inv, transpose(ref(inv)));
  }
}

TEST_CASE("inverse_spd of a singular matrix is not finite", "[math]") {
  const Matrix3x3<double> m(1, 1, 0, 1, 1, 0, 0, 0, 1);  // rows 0 and 1 equal
  const Matrix3x3<double> inv = inverse_spd(m);
  CHECK_FALSE(std::isfinite(inv[0]));
}

TEMPLATE_TEST_CASE("R I R^T rotates a tensor", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(24);
  for (int n = 0; n < repeats; ++n) {
    const Matrix3x3<T> r = to_rotation_matrix(random_unit_quaternion<T>(rng));
    const Matrix3x3<T> inertia = random_spd<T>(rng);
    require_close(rotate_tensor(r, inertia), matmul(matmul(ref(r), ref(inertia)), transpose(ref(r))));
  }
}

TEST_CASE("matrix factories", "[math]") {
  const Matrix3x3<double> d = Matrix3x3<double>::diagonal(2, 3, 4);
  for (std::size_t r = 0; r < 3; ++r)
    for (std::size_t c = 0; c < 3; ++c) CHECK(d(r, c) == (r == c ? 2.0 + r : 0.0));
  const Matrix3x3<float> i = Matrix3x3<float>::identity();
  CHECK((i(0, 0) == 1 && i(1, 1) == 1 && i(2, 2) == 1 && i(0, 1) == 0 && i(2, 0) == 0));
  const Matrix3x3<float> m(1, 2, 3, 4, 5, 6, 7, 8, 9);
  CHECK((m(0, 2) == 3 && m(1, 0) == 4 && m(2, 1) == 8));
}
