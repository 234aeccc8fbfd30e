// The atlas's scenes as BodySets: the shared sphere pile of PILE.md (the scene
// peer engines were measured on) and a column of spheres of alternating mass.
#pragma once

#include <cmath>
#include <cstddef>
#include <random>

#include "gpusolve/rbd/bodies/body_set.hpp"

namespace gpusolve::bench {

// N spheres (radius 1, mass 1) on a jittered cubic lattice of spacing 2.1 in an
// open box of planes, exactly as the shared pile specification prescribes: side
// L = ceil(cbrt N), sphere i at lattice (i mod L, (i / L) mod L, i / L^2) plus
// jitters (jx, jy, jz) from std::mt19937(1) and uniform_real_distribution(-0.05,
// 0.05), the floor z = 0 and walls x, y = +-h with h = (L s + 0.2) / 2.
template <class T>
rbd::BodySet<T> shared_pile(std::size_t n) {
  const std::size_t L = std::size_t(std::ceil(std::cbrt(double(n)) - 1e-9));
  const double s = 2.1;
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  rbd::BodySet<T> set;
  const double c0 = -(double(L) - 1) * s / 2;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t x = i % L, y = (i / L) % L, z = i / (L * L);
    const double jx = jitter(gen), jy = jitter(gen), jz = jitter(gen);
    set.add_sphere({T(c0 + x * s + jx), T(c0 + y * s + jy), T(1.1 + z * s + jz)}, T(1), T(1));
  }
  const T h = T((double(L) * s + 0.2) / 2);
  set.add_plane({0, 0, 1}, 0);
  set.add_plane({1, 0, 0}, -h);  // n.x = d: the wall x = -h, solid below
  set.add_plane({-1, 0, 0}, -h);
  set.add_plane({0, 1, 0}, -h);
  set.add_plane({0, -1, 0}, -h);
  return set;
}

// `count` spheres of radius 1 stacked on the floor, exactly aligned, masses
// alternating 1 (the bottom one) and `ratio`: heavy on light is the classic case
// where iterative contact solvers need many iterations.
template <class T>
rbd::BodySet<T> mass_column(std::size_t count, double ratio) {
  rbd::BodySet<T> set;
  for (std::size_t k = 0; k < count; ++k) set.add_sphere({0, 0, T(1 + 2 * k)}, T(1), T(k % 2 ? ratio : 1.0));
  set.add_plane({0, 0, 1}, 0);
  return set;
}

}  // namespace gpusolve::bench
