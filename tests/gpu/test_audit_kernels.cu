// The audited kernels (tests/audit) compute what they claim: every variant of
// the vector triad and of Eq. (9), and every way of passing their descriptors,
// against the host computing the same expressions in long double.
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

#include "../audit/audit_kernels.cuh"
#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;
using namespace gpusolve_audit;

namespace {

constexpr std::size_t n = 1000;  // not a multiple of the block size
// Launches and waits, so the result can be copied back.
template <class Body>
void run(const Body& body, Pass pass) {
  launch_each_element(body, pass);
  GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
}

template <class T>
VectorD2<T> random3(std::mt19937& gen) {
  std::uniform_real_distribution<T> dist(-2, 2);
  VectorD2<T> h(n, 3);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < n; ++i) h(i, k) = dist(gen);
  return h;
}

// |got - want| within a few roundings of the terms' magnitude (FMA contraction
// and evaluation order differ between the kernel and the reference).
template <class T>
void require_close(T got, long double want, long double scale, std::size_t i, std::size_t k) {
  const long double tol = 16 * std::numeric_limits<T>::epsilon() * (scale + 1);
  INFO("element (" << i << ", " << k << "): got " << got << ", want " << static_cast<double>(want));
  REQUIRE(std::fabs(static_cast<long double>(got) - want) <= tol);
}

template <class T>
void check_triad(const VectorD2<T>& got, const VectorD2<T>& b, const VectorD1<T>& c, const VectorD2<T>& d) {
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      const long double cd = static_cast<long double>(c(i)) * d(i, k);
      require_close(got(i, k), b(i, k) + cd, std::fabs(b(i, k)) + std::fabs(cd), i, k);
    }
}

template <class T>
void check_contact(const VectorD2<T>& got, const VectorD2<T>& q, const VectorD2<T>& v,
                   const VectorD2<T>& r, const VectorD2<T>& w, T dt) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t j = (k + 1) % 3, l = (k + 2) % 3;
      const long double cross = static_cast<long double>(r(i, j)) * w(i, l) -
                                static_cast<long double>(r(i, l)) * w(i, j);
      const long double want =
          q(i, k) + static_cast<long double>(v(i, k)) * dt + r(i, k) - cross * dt;
      const long double scale = std::fabs(q(i, k)) + std::fabs(v(i, k) * dt) + std::fabs(r(i, k)) +
                                (std::fabs(r(i, j) * w(i, l)) + std::fabs(r(i, l) * w(i, j))) * dt;
      require_close(got(i, k), want, scale, i, k);
    }
}

}  // namespace

TEMPLATE_TEST_CASE("audit kernels: the vector triad a = b + c d in every variant", "[audit][gpu]", float,
                   double) {
  using T = TestType;
  std::mt19937 gen(4);
  const VectorD2<T> b = random3<T>(gen), d = random3<T>(gen);
  VectorD1<T> c(n);
  std::uniform_real_distribution<T> dist(-2, 2);
  for (std::size_t i = 0; i < n; ++i) c(i) = dist(gen);

  VectorD2<T, device::gpu> ad(n, 3), bd(b), dd(d);
  VectorD1<T, device::gpu> cd(c);
  const TriadArgs<T> args{ad.view(), bd.view(), dd.view(), cd.view(), Offset3::of(ad.view())};
  REQUIRE(bd.pitch() == ad.pitch());  // one offset object serves a, b and d
  REQUIRE(dd.pitch() == ad.pitch());

  const auto check = [&](auto body, Pass pass) {
    ad.fill(std::numeric_limits<T>::quiet_NaN());
    run(body, pass);
    const VectorD2<T> got(ad);
    check_triad(got, b, c, d);
  };
  SECTION("plain C++") { check(TriadPlain<T>{args}, Pass::by_value); }
  SECTION("expression templates, by value") { check(TriadET<T>{args}, Pass::by_value); }
  SECTION("expression templates, __grid_constant__") { check(TriadET<T>{args}, Pass::grid_constant); }
  SECTION("expression templates, ConstantDeviceMemory") { check(TriadET<T>{args}, Pass::constant_memory); }
}

TEMPLATE_TEST_CASE("audit kernels: Eq. (9) p = q + v dt + r - (r x w) dt in every variant", "[audit][gpu]",
                   float, double) {
  using T = TestType;
  std::mt19937 gen(9);
  const VectorD2<T> q = random3<T>(gen), v = random3<T>(gen), r = random3<T>(gen), w = random3<T>(gen);
  const T dt = T(0.0025);

  VectorD2<T, device::gpu> pd(n, 3), qd(q), vd(v), rd(r), wd(w);
  for (std::size_t pitch : {qd.pitch(), vd.pitch(), rd.pitch(), wd.pitch()}) REQUIRE(pitch == pd.pitch());
  const ContactArgs<T> args{pd.view(), qd.view(), vd.view(), rd.view(), wd.view(), Offset3::of(pd.view()), dt};

  const auto check = [&](auto body, Pass pass) {
    pd.fill(std::numeric_limits<T>::quiet_NaN());
    run(body, pass);
    const VectorD2<T> got(pd);
    check_contact(got, q, v, r, w, dt);
  };
  SECTION("plain C++") { check(ContactPlain<T>{args}, Pass::by_value); }
  SECTION("expression templates on Globals") { check(ContactET<T>{args}, Pass::by_value); }
  SECTION("expression templates written through") { check(ContactETWriteThrough<T>{args}, Pass::by_value); }
  SECTION("cached, by value") { check(ContactCached<T>{args}, Pass::by_value); }
  SECTION("cached, __grid_constant__") { check(ContactCached<T>{args}, Pass::grid_constant); }
  SECTION("cached, ConstantDeviceMemory") { check(ContactCached<T>{args}, Pass::constant_memory); }

  SECTION("Global-only ET stays right when p is r") {
    // The cross product reads r after p's first element is written: assign()'s
    // temporary is what makes this safe (and what saves the reloads).
    ContactArgs<T> aliased = args;
    aliased.p = aliased.r;
    run(ContactET<T>{aliased}, Pass::by_value);
    const VectorD2<T> got(rd);
    check_contact(got, q, v, r, w, dt);
  }
}
