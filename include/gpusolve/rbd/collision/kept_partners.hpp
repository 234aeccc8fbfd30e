// The count pass of collision detection: each body walks its partners,
// counts them and keeps the first few, sorted, for the write pass to read
// instead of walking again.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd::detail {

// The pairs a count pass keeps per body (the b bodies, sorted), so that the
// write pass reads them instead of walking the grid a second time; a body with
// more walks again, and the write pass waits for its longest walk. An
// equal sphere touches at most 12 others, about half of them with a larger
// index, and a few walls: the contact walk of spheres keeps 8. A box's
// candidates (bounding spheres within the margin, past its slabs' test, and
// the planes) run to 14 in the shared cube pile (docs/detection.md): the
// candidate walk keeps 16, at no register more.
inline constexpr std::uint32_t kept_contacts = 8;
inline constexpr std::uint32_t kept_candidates = 16;
static_assert(kept_candidates >= kept_contacts, "the store of kept partners is sized for the candidates");

// Insertion sort of a body's few partners, in place.
template <class Get, class Set>
GPUSOLVE_HD void sort_few(std::uint32_t first, std::uint32_t last, Get get, Set set) {
  for (std::uint32_t p = first + 1; p < last; ++p) {
    const std::uint32_t j = get(p);
    std::uint32_t q = p;
    for (; q > first && get(q - 1) > j; --q) set(q, get(q - 1));
    set(q, j);
  }
}

// Inserts j into the sorted found[0, c) (c < Kept). found is indexed only in
// unrolled loops, so that it stays in registers: a position p takes its own
// body while that is below j, j where the bodies below end, and its left
// neighbour's after.
template <std::uint32_t Kept>
GPUSOLVE_HD void insert_sorted(std::uint32_t (&found)[Kept], std::uint32_t c, std::uint32_t j) {
  GPUSOLVE_UNROLL
  for (int p = int(Kept) - 1; p >= 0; --p) {
    const std::uint32_t up = std::uint32_t(p);
    if (up > c) continue;
    const bool stays = up < c && found[p] < j;
    const bool here = p == 0 || found[p > 0 ? p - 1 : 0] < j;
    found[p] = stays ? found[p] : here ? j : found[p > 0 ? p - 1 : 0];
  }
}

// Counts body i's partners, those walk(i, visit) visits (count[i]), and keeps
// the first Kept of them, sorted, at kept[c * n + i] (c = 0, 1, ...: a warp's
// stores are contiguous).
template <class Walk, std::uint32_t Kept = kept_contacts>
struct CountPartners {
  Walk walk;
  std::uint32_t* count;
  std::uint32_t* kept;
  std::size_t n;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t found[Kept] = {};
    std::uint32_t partners = 0;
    walk(i, [&](std::uint32_t j) {
      if (partners < Kept) insert_sorted<Kept>(found, partners, j);
      ++partners;
    });
    GPUSOLVE_UNROLL
    for (std::uint32_t p = 0; p < Kept; ++p)
      if (p < partners) kept[p * n + i] = found[p];
    count[i] = partners;
  }
};

}  // namespace gpusolve::rbd::detail
