// Host containers: element access, fill, resize, bounds checks, copies across layouts, shape errors, interop.
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
using Debug = compiletime_policy_is<compiletime::DebugPolicy>;

template <class C>
void fill_random_2d(C& c, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1e3, 1e3);
  for (std::size_t j = 0; j < c.size_y(); ++j)
    for (std::size_t i = 0; i < c.size_x(); ++i) c(i, j) = static_cast<typename C::value_type>(dist(gen));
}
}  // namespace

TEST_CASE("new and resized containers are zero; element (i, j) is data()[j * pitch + i]", "[container]") {
  VectorD2<double> a(33, 4);
  for (std::size_t k = 0; k < a.allocated(); ++k) REQUIRE(a.data()[k] == 0.0);
  a(5, 3) = 1.5;
  CHECK(a.data()[3 * a.pitch() + 5] == 1.5);
  CHECK(a.view()(5, 3) == 1.5);
  a.resize(70, 2);
  CHECK(a.size_x() == 70);
  CHECK(a.size_y() == 2);
  CHECK(a.pitch() == 96);
  for (std::size_t k = 0; k < a.allocated(); ++k) REQUIRE(a.data()[k] == 0.0);

  VectorD3<int> v(3, 4, 5);
  v(2, 3, 4) = 7;
  CHECK(v.data()[(4 * v.padded_y() + 3) * v.pitch() + 2] == 7);
  CHECK(v.view()(2, 3, 4) == 7);

  VectorD2<float> empty;
  CHECK(empty.empty());
  CHECK(empty.data() == nullptr);
  CHECK(empty.allocated() == 0);
}

TEST_CASE("fill sets every logical element and leaves the padding zero", "[container]") {
  VectorD2<float> a(33, 3);
  a.fill(2.5f);
  for (std::size_t j = 0; j < 3; ++j) {
    for (std::size_t i = 0; i < 33; ++i) REQUIRE(a(i, j) == 2.5f);
    for (std::size_t i = 33; i < a.pitch(); ++i) REQUIRE(a.data()[j * a.pitch() + i] == 0.0f);
  }
  VectorD3<int, layout_is<layout::PadAll<4, 4, 4>>> b(3, 3, 3);
  b.fill(-4);
  int sum = 0;
  for (std::size_t k = 0; k < b.allocated(); ++k) sum += b.data()[k];
  CHECK(sum == -4 * 27);
  VectorD1<long> c(40);
  c.fill(9);
  CHECK(std::count(c.begin(), c.end(), 9L) == 40);
  CHECK(c.end() - c.begin() == 40);
}

TEST_CASE("debug policy: out-of-bounds host access throws with indices and extents", "[container][bounds]") {
  VectorD2<double, Debug> a(10, 3);
  CHECK_NOTHROW(a(9, 2));
  try {
    a(10, 1);
    FAIL("no BoundsError");
  } catch (const BoundsError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("(10, 1)") != std::string::npos);
    CHECK(msg.find("(10, 3)") != std::string::npos);
  }
  CHECK_THROWS_AS(a(0, 3), BoundsError);
  VectorD1<int, Debug> b(4);
  CHECK_THROWS_AS(b[4], BoundsError);
  VectorD3<int, Debug> c(2, 3, 4);
  try {
    c(1, 2, 4);
    FAIL("no BoundsError");
  } catch (const BoundsError& e) {
    CHECK(std::string(e.what()).find("(1, 2, 4)") != std::string::npos);
    CHECK(std::string(e.what()).find("(2, 3, 4)") != std::string::npos);
  }
  // Release: no check, the access lands in the padding of row 1 (pitch 32).
  VectorD2<double> r(10, 3);
  CHECK_NOTHROW(r(10, 1));
  CHECK(&r(10, 1) == r.data() + r.pitch() + 10);
}

TEST_CASE("host-to-host copies between layouts keep every logical element", "[container][copy]") {
  for (std::size_t nx : {1u, 31u, 32u, 33u, 65u}) {
    VectorD2<double> a(nx, 5);
    fill_random_2d(a, static_cast<unsigned>(nx));
    VectorD2<double, layout_is<layout::NoPadding>> b(nx, 5);
    b = a;
    VectorD2<double, layout_is<layout::PadAll<16, 8>>, Debug> c(nx, 5);
    c = b;
    VectorD2<double> d(nx, 5);
    d = c;  // equal layouts: one contiguous block
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        REQUIRE(b(i, j) == a(i, j));
        REQUIRE(c(i, j) == a(i, j));
        REQUIRE(d(i, j) == a(i, j));
      }
    // Padding is not written by layout-changing copies.
    for (std::size_t k = 0; k < c.allocated(); ++k)
      if (k % c.pitch() >= nx || k / c.pitch() >= 5) REQUIRE(c.data()[k] == 0.0);
  }
  VectorD3<float, layout_is<layout::PadAll<8, 4, 2>>> s(9, 5, 3);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < 9; ++i) s(i, j, k) = float(i + 10 * j + 100 * k);
  VectorD3<float, layout_is<layout::NoPadding>> t(9, 5, 3);
  t = s;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < 9; ++i) REQUIRE(t(i, j, k) == float(i + 10 * j + 100 * k));
}

TEST_CASE("copy constructors, converting constructors and assignment to an empty container", "[container][copy]") {
  VectorD1<int> a(50);
  std::iota(a.begin(), a.end(), 3);
  VectorD1<int> b(a);  // deep
  a(0) = -1;
  CHECK(b(0) == 3);
  CHECK(b(49) == 52);
  VectorD1<int, layout_is<layout::NoPadding>> c(b);  // converting
  CHECK(c.size() == 50);
  CHECK(c(49) == 52);
  VectorD1<int> d;
  d = c;  // empty destination takes the source's shape
  CHECK(d.size() == 50);
  CHECK(std::equal(d.begin(), d.end(), b.begin()));
  VectorD1<int> moved(std::move(d));
  CHECK(moved.size() == 50);
  CHECK(d.empty());
}

TEST_CASE("copies between different logical shapes throw SizeMismatchError naming both", "[container][copy]") {
  VectorD2<double> a(10, 3), b(10, 4);
  try {
    b = a;
    FAIL("no SizeMismatchError");
  } catch (const SizeMismatchError& e) {
    const std::string msg = e.what();
    CHECK(msg.find("10 x 3") != std::string::npos);
    CHECK(msg.find("10 x 4") != std::string::npos);
  }
  VectorD2<double, layout_is<layout::NoPadding>> c(11, 3);
  CHECK_THROWS_AS(copy(c, a), SizeMismatchError);
  CHECK_THROWS_AS(copy_async(c, a, stream_t{}), SizeMismatchError);
  CHECK(c.size_x() == 11);  // untouched
}

TEST_CASE("host HostMemory with the standard allocator", "[container][memory]") {
  memory::HostMemory<double> m(100);
  CHECK(m.size() == 100);
  CHECK(m.bytes() == 800);
  m(99) = 4.0;
  CHECK(m.data()[99] == 4.0);
  CHECK(m(0) == 0.0);
}

#if GPUSOLVE_HAS_MDSPAN
TEST_CASE("mdspan view strides by the padding", "[container][mdspan]") {
  VectorD2<double> a(33, 3);
  a(32, 2) = 6.0;
  auto m = a.mdspan();
  CHECK(m.extent(0) == 33);
  CHECK(m.extent(1) == 3);
  CHECK(m.stride(1) == a.pitch());
  CHECK(m(32, 2) == 6.0);
  VectorD3<int, layout_is<layout::PadAll<4, 4, 1>>> b(3, 3, 2);
  b(2, 1, 1) = 5;
  const auto& cb = b;
  auto mb = cb.mdspan();
  CHECK(mb.stride(2) == 16);
  CHECK(mb(2, 1, 1) == 5);
}
#endif
