// Padding policies: padded extents around block multiples, and the pitches containers take from them.
#include <cstddef>
#include <cstdint>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
// A user layout: x padded to an odd block, y to at least 4 rows.
struct OddLayout {
  static constexpr std::size_t padded(std::size_t n, int dim) {
    return dim == 0 ? (n + 6) / 7 * 7 : (n < 4 ? 4 : n);
  }
};
}  // namespace

TEST_CASE("PadFirst pads x to the next block multiple and leaves y and z", "[container][layout]") {
  using L = layout::PadFirst<32>;
  STATIC_REQUIRE(L::padded(0, 0) == 0);
  STATIC_REQUIRE(L::padded(1, 0) == 32);
  STATIC_REQUIRE(L::padded(31, 0) == 32);
  STATIC_REQUIRE(L::padded(32, 0) == 32);
  STATIC_REQUIRE(L::padded(33, 0) == 64);
  STATIC_REQUIRE(L::padded(63, 0) == 64);
  STATIC_REQUIRE(L::padded(64, 0) == 64);
  STATIC_REQUIRE(L::padded(65, 0) == 96);
  STATIC_REQUIRE(L::padded(33, 1) == 33);
  STATIC_REQUIRE(L::padded(65, 2) == 65);
  STATIC_REQUIRE(layout::PadFirst<>::padded(33, 0) == 64);  // the default block is a warp
  STATIC_REQUIRE(layout::PadFirst<16>::padded(17, 0) == 32);
}

TEST_CASE("PadAll pads every dimension to its own block (thesis Fig. 6)", "[container][layout]") {
  using L = layout::PadAll<16, 8, 4>;
  STATIC_REQUIRE(L::padded(28, 0) == 32);  // the thesis's 28 x 14 input padded to 32 x 16
  STATIC_REQUIRE(L::padded(14, 1) == 16);
  STATIC_REQUIRE(L::padded(31, 0) == 32);
  STATIC_REQUIRE(L::padded(32, 0) == 32);
  STATIC_REQUIRE(L::padded(33, 0) == 48);
  STATIC_REQUIRE(L::padded(63, 1) == 64);
  STATIC_REQUIRE(L::padded(64, 1) == 64);
  STATIC_REQUIRE(L::padded(65, 1) == 72);
  STATIC_REQUIRE(L::padded(5, 2) == 8);
  STATIC_REQUIRE(layout::NoPadding::padded(33, 0) == 33);
  STATIC_REQUIRE(layout::is_layout_v<OddLayout>);
  STATIC_REQUIRE(!layout::is_layout_v<int>);
}

TEST_CASE("containers take pitch and padded extents from their layout", "[container][layout]") {
  for (std::size_t nx : {31u, 32u, 33u, 63u, 64u, 65u}) {
    VectorD2<float> a(nx, 3);
    CHECK(a.size_x() == nx);
    CHECK(a.size_y() == 3);
    CHECK(a.pitch() == (nx + 31) / 32 * 32);
    CHECK(a.pitch() % 32 == 0);
    CHECK(a.pitch() >= nx);
    CHECK(a.pitch() - nx < 32);
    CHECK(a.allocated() == a.pitch() * 3);
    // Every row starts 128-byte aligned on the host too.
    for (std::size_t j = 0; j < 3; ++j)
      CHECK(reinterpret_cast<std::uintptr_t>(&a(0, j)) % 128 == 0);

    VectorD2<double, layout_is<layout::NoPadding>> b(nx, 3);
    CHECK(b.pitch() == nx);
    CHECK(b.allocated() == nx * 3);

    VectorD3<int, layout_is<layout::PadAll<16, 8, 4>>> c(nx, 9, 5);
    CHECK(c.pitch() == (nx + 15) / 16 * 16);
    CHECK(c.padded_y() == 16);
    CHECK(c.padded_z() == 8);
    CHECK(c.allocated() == c.pitch() * 16 * 8);
    CHECK(c.size() == nx * 9 * 5);
  }
  VectorD2<char, layout_is<OddLayout>> d(8, 2);
  CHECK(d.pitch() == 14);
  CHECK(d.padded_y() == 4);
  VectorD1<float> e(33);
  CHECK(e.pitch() == 64);
  CHECK(e.size() == 33);
}
