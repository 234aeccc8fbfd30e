// Quaternion operators and rotations against double-precision references.
#include <cmath>
#include <cstddef>
#include <random>

#include "catch_compat.hpp"
#include "gpusolve/math.hpp"
#include "test_math_support.hpp"

using namespace gpusolve::math;
using namespace math_test;

TEMPLATE_TEST_CASE("quaternion operators match a double reference", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(31);
  for (int n = 0; n < repeats; ++n) {
    const Quaternion<T> p = random_unit_quaternion<T>(rng), q = random_unit_quaternion<T>(rng);
    const Vector3<T> v = random_vector<T>(rng);
    const T s = uniform<T>(rng, 0.5, 2);
    const R4 rp = ref(p), rq = ref(q);

    require_close(Quaternion<T>(p * q), qmul(rp, rq));
    require_close(Quaternion<T>(p + s * q), lin(1, rp, s, rq));
    require_close(Quaternion<T>(conj(p)), R4{rp[0], -rp[1], -rp[2], -rp[3]});
    require_close(Quaternion<T>(p * conj(p)), R4{1, 0, 0, 0});
    require_close(Quaternion<T>(normalize(p * s)), rp);
    require_close(rotate(p, v), qrotate(rp, ref(v)));
    require_close(rotate(p * q, v), qrotate(rp, qrotate(rq, ref(v))));
  }
}

TEMPLATE_TEST_CASE("quaternion assignments that read their target", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(32);
  for (int n = 0; n < repeats; ++n) {
    Quaternion<T> q = random_unit_quaternion<T>(rng);
    const Quaternion<T> p = random_unit_quaternion<T>(rng);
    R4 r = ref(q);
    q = q * p;        r = qmul(r, ref(p));     require_close(q, r);
    q = p * q;        r = qmul(ref(p), r);     require_close(q, r);
    q = q * conj(q);  r = qmul(r, R4{r[0], -r[1], -r[2], -r[3]}); require_close(q, r);
  }
}

TEMPLATE_TEST_CASE("quaternion and rotation matrix convert both ways", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(33);
  for (int n = 0; n < repeats; ++n) {
    const Quaternion<T> q = random_unit_quaternion<T>(rng);
    const Matrix3x3<T> m = to_rotation_matrix(q);
    require_close(m, qmatrix(ref(q)));
    const Quaternion<T> back = to_quaternion(m);
    // q and -q are the same rotation
    require_close_scalar(std::abs(dot(ref(back), ref(q))), 1, 4 * tol<T>());
    require_close(to_rotation_matrix(back), ref(m));
  }
  // every branch of to_quaternion: half turns about x, y, z and the identity
  for (int axis = 0; axis < 4; ++axis) {
    R3 k{0, 0, 0};
    if (axis < 3) k[axis] = 1;
    const R9 r = rodrigues(axis < 3 ? k : R3{1, 0, 0}, axis < 3 ? 3.0 : 0.0);
    Matrix3x3<T> m;
    for (std::size_t i = 0; i < 9; ++i) m[i] = static_cast<T>(r[i]);
    require_close(to_rotation_matrix(to_quaternion(m)), r);
  }
}

TEMPLATE_TEST_CASE("axis-angle gives the Rodrigues rotation", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(34);
  for (int n = 0; n < repeats; ++n) {
    const Vector3<T> axis = normalize(random_vector<T>(rng));
    const T angle = uniform<T>(rng, -3, 3);
    const Quaternion<T> q = Quaternion<T>::from_axis_angle(axis, angle);
    require_close(to_rotation_matrix(q), rodrigues(ref(axis), angle));
    require_close_scalar(norm(q), 1, tol<T>());
  }
}

TEMPLATE_TEST_CASE("orientation update is the exact exponential map", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(35);
  for (int n = 0; n < repeats; ++n) {
    const Quaternion<T> q = random_unit_quaternion<T>(rng);
    const Vector3<T> w = random_vector<T>(rng) * T(10);
    const T dt = uniform<T>(rng, 1e-3, 0.1);
    const Quaternion<T> next = integrate_orientation(q, w, dt);
    const R3 rw = ref(w);
    const double speed = std::sqrt(dot(rw, rw));
    const R9 expected = matmul(rodrigues(lin(1 / speed, rw, 0, rw), speed * dt), qmatrix(ref(q)));
    require_close(to_rotation_matrix(next), expected);
    require_close_scalar(norm(next), 1, tol<T>());
  }
}

TEMPLATE_TEST_CASE("orientation update at small and zero angular velocity", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(36);
  const Quaternion<T> q = random_unit_quaternion<T>(rng);
  // |w| dt across the switch to the series, down to zero
  for (double speed : {1e-1, 1e-2, 1e-3, 1e-4, 1e-6, 1e-9, 1e-20, 0.0}) {
    const Vector3<T> axis = normalize(random_vector<T>(rng));
    const Vector3<T> w = axis * T(speed);
    const T dt = T(0.5);
    const Quaternion<T> next = integrate_orientation(q, w, dt);
    const double half = speed * double(dt) / 2, s = std::sin(half);
    const R4 turn{std::cos(half), s * double(axis[0]), s * double(axis[1]), s * double(axis[2])};
    INFO("|w| = " << speed);
    require_close(next, qmul(turn, ref(q)));
    // From the identity the result is the turn itself: its small vector part
    // must be right to a few roundings relative to its own size.
    const Quaternion<T> alone = integrate_orientation(Quaternion<T>::identity(), w, dt);
    const double eps = sizeof(T) == sizeof(float) ? 1.2e-7 : 2.3e-16;
    for (std::size_t k = 0; k < 4; ++k) {
      INFO("element " << k << ": got " << alone[k] << ", expected " << turn[k]);
      CHECK(std::abs(alone[k] - turn[k]) <= 8 * eps * std::abs(turn[k]));
    }
  }
}

TEST_CASE("quaternion identity is the rotation none", "[math]") {
  const Quaternion<double> i = Quaternion<double>::identity();
  const Vector3<double> v(1, 2, 3);
  require_close(rotate(i, v), R3{1, 2, 3});
}
