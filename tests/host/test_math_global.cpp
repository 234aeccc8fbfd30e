// Global types over a padded host VectorD2 layout: they read and write the
// right addresses, mix with value types, and stay correct under aliasing.
#include <cstddef>
#include <random>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/policy/compiletime.hpp"
#include "test_math_support.hpp"

using namespace gpusolve;
using namespace gpusolve::math;
using namespace math_test;

namespace {

constexpr std::size_t nx = 37, pitch = 64;
constexpr double padding_mark = -12345;

// A structure-of-arrays block of N rows over host memory, with its logical
// elements random and its padding marked.
template <class T, class Kind, class Check = compiletime::ReleasePolicy>
struct HostSoA {
  static constexpr std::size_t N = Kind::size;
  std::vector<T> data;
  VectorD2View<T, Check> view;
  VectorD2Offset<N> offset;

  explicit HostSoA(std::mt19937& rng)
      : data(N * pitch, T(padding_mark)), view{data.data(), nx, N, pitch}, offset(pitch) {
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t i = 0; i < nx; ++i) view(i, j) = uniform<T>(rng);
  }
  Global<Kind, T, Check> at(std::size_t i) { return {view, offset, i}; }
  bool padding_intact() const {
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t i = nx; i < pitch; ++i)
        if (data[j * pitch + i] != T(padding_mark)) return false;
    return true;
  }
};

}  // namespace

TEMPLATE_TEST_CASE("a Global reads and writes entry (index, k) of its VectorD2", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(41);
  HostSoA<T, MatrixKind> m(rng);
  for (std::size_t i = 0; i < nx; ++i) {
    const auto g = m.at(i);
    for (std::size_t k = 0; k < 9; ++k) CHECK(&g[k] == &m.data[k * pitch + i]);
  }
  const Matrix3x3<T> value = m.at(5);
  Matrix3x3Global<T> g = m.at(6);
  g = value;  // writes values: entry 6 now equals entry 5, entry 5 is untouched
  for (std::size_t k = 0; k < 9; ++k) CHECK(m.view(6, k) == m.view(5, k));
  g = m.at(7);  // Global to Global assigns values too, it does not rebind
  for (std::size_t k = 0; k < 9; ++k) CHECK(m.view(6, k) == m.view(7, k));
  m.view(7, 0) += 1;
  CHECK(g[0] != m.view(7, 0));
  CHECK(m.padding_intact());
}

TEMPLATE_TEST_CASE("expressions over Global and value types", "[math]", float, double) {
  using T = TestType;
  std::mt19937 rng(42);
  HostSoA<T, VectorKind> x(rng), v(rng), w(rng);
  HostSoA<T, MatrixKind> rot(rng), inertia(rng);
  HostSoA<T, QuaternionKind> q(rng);
  const T dt = T(0.01);
  for (std::size_t i = 0; i < nx; ++i) {
    auto xg = x.at(i), vg = v.at(i), wg = w.at(i);
    auto rg = rot.at(i), ig = inertia.at(i);
    auto qg = q.at(i);
    const Vector3<T> r = random_vector<T>(rng);  // cached in registers (Table 5)
    const Quaternion<T> p = random_unit_quaternion<T>(rng);
    const Matrix3x3<T> n = random_matrix<T>(rng);
    R3 rx = ref(xg), rv = ref(vg), rw = ref(wg);
    R9 rr = ref(rg), ri = ref(ig);
    R4 rq = ref(qg);

    xg = xg + vg * dt + r - (r % wg) * dt;  // thesis Eq. (9)
    rx = lin(1, lin(1, rx, dt, rv), 1, lin(1, ref(r), -double(dt), cross(ref(r), rw)));
    require_close(xg, rx);
    wg = vg % wg;  rw = cross(rv, rw);  require_close(wg, rw);
    vg = rg * vg;  rv = matvec(rr, rv);  require_close(vg, rv);
    vg = transpose(rg) * (ig * vg) - r;  rv = lin(1, matvec(transpose(rr), matvec(ri, rv)), -1, ref(r));
    require_close(vg, rv);
    rg = rg * n;  rr = matmul(rr, ref(n));  require_close(rg, rr);
    rg = ig * rg;  rr = matmul(ri, rr);  require_close(rg, rr);
    ig = transpose(ig);  ri = transpose(ri);  require_close(ig, ri);
    qg = qg * p;  rq = qmul(rq, ref(p));  require_close(qg, rq);
    qg = normalize(qg);  rq = lin(1 / std::sqrt(dot(rq, rq)), rq, 0, rq);  require_close(qg, rq);
    xg += vg;  rx = lin(1, rx, 1, rv);  require_close(xg, rx);
    xg -= r * T(2);  rx = lin(1, rx, -2, ref(r));  require_close(xg, rx);
    xg *= T(3);  rx = lin(3, rx, 0, rx);  require_close(xg, rx);
    xg /= T(2);  rx = lin(0.5, rx, 0, rx);  require_close(xg, rx);
    require_close_scalar(dot(xg, r), dot(rx, ref(r)), tol<T>());
    require_close(rotate(qg, vg), qrotate(rq, rv));
  }
  CHECK(x.padding_intact());
  CHECK(v.padding_intact());
  CHECK(w.padding_intact());
  CHECK(rot.padding_intact());
  CHECK(inertia.padding_intact());
  CHECK(q.padding_intact());
}

TEST_CASE("a debug-policy Global rejects an index outside its VectorD2", "[math]") {
  std::mt19937 rng(43);
  HostSoA<double, VectorKind, compiletime::DebugPolicy> a(rng);
  CHECK_NOTHROW((Vector3Global<double, compiletime::DebugPolicy>(a.view, a.offset, nx - 1)));
  CHECK_THROWS_AS((Vector3Global<double, compiletime::DebugPolicy>(a.view, a.offset, nx)), BoundsError);
  // a width-3 VectorD2 cannot hold quaternions
  const VectorD2Offset<4> offset4(pitch);
  CHECK_THROWS_AS((QuaternionGlobal<double, compiletime::DebugPolicy>(a.view, offset4, 0)), BoundsError);
}
