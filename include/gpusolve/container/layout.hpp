// Memory layout (padding) policies: how far each dimension of a container is padded.
#pragma once

#include <cstddef>
#include <type_traits>

namespace gpusolve::layout {

// The layout concept. A user policy is any class with
//   static std::size_t padded(std::size_t n, int dim);   // dim 0 = x, 1 = y, 2 = z
// returning the allocated extent (>= n) of dimension `dim` whose logical extent is n.
// x is contiguous, so padded(nx, 0) is the pitch of a row in elements.

namespace detail {
constexpr std::size_t round_up(std::size_t n, std::size_t block) {
  return (n + block - 1) / block * block;
}
}  // namespace detail

// Every extent as is: the densest layout, rows aligned only by accident.
struct NoPadding {
  static constexpr std::size_t padded(std::size_t n, int) { return n; }
};

// Pads x to a multiple of Block elements so every row starts where a warp's
// coalesced access wants it: with the default 32, float and double rows start
// on 128-byte boundaries.
template <std::size_t Block = 32>
struct PadFirst {
  static_assert(Block > 0, "gpusolve: PadFirst needs a block size > 0");
  static constexpr std::size_t padded(std::size_t n, int dim) {
    return dim == 0 ? detail::round_up(n, Block) : n;
  }
};

// Pads every dimension to a multiple of its block (thesis Fig. 6): kernels that
// process whole thread blocks may then read and write past the logical end.
template <std::size_t BX, std::size_t BY = 1, std::size_t BZ = 1>
struct PadAll {
  static_assert(BX > 0 && BY > 0 && BZ > 0, "gpusolve: PadAll needs block sizes > 0");
  static constexpr std::size_t padded(std::size_t n, int dim) {
    return detail::round_up(n, dim == 0 ? BX : dim == 1 ? BY : BZ);
  }
};

template <class L, class = void>
struct is_layout : std::false_type {};
template <class L>
struct is_layout<L, std::void_t<decltype(std::size_t{L::padded(std::size_t{}, 0)})>> : std::true_type {};
template <class L>
inline constexpr bool is_layout_v = is_layout<L>::value;

}  // namespace gpusolve::layout
