// Random sphere clouds and a brute-force pair search, shared by the host and GPU collision tests.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "gpusolve/rbd/bodies/body_set.hpp"

namespace rbd_test {

// n spheres in a cube of side `extent` with radii in [rmin, rmax] (a few of them
// four times larger, so spheres span cell boundaries and cells differ in size),
// every seventh one fixed, every eleventh one removed, inside a box of planes
// with a fixed box obstacle in the middle.
inline gpusolve::rbd::BodySet<float> random_cloud(unsigned seed, int n, float extent, float rmin = 0.1f,
                                                  float rmax = 0.4f) {
  gpusolve::rbd::BodySet<float> s;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(0.f, extent), rad(rmin, rmax), speed(-1.f, 1.f);
  for (int i = 0; i < n; ++i) {
    const float r = (i % 37 == 5) ? 4 * rmax : rad(rng);
    const std::array<float, 3> p{pos(rng), pos(rng), pos(rng)};
    const std::size_t k = (i % 7 == 3) ? s.add_fixed_sphere(p, r) : s.add_sphere(p, r, 1.f + r);
    if (s[k].status == gpusolve::rbd::active) s[k].v = {speed(rng), speed(rng), speed(rng)};
    if (i % 11 == 4) s[k].status = gpusolve::rbd::removed;
  }
  s.add_plane({0.f, 0.f, 1.f}, 0.f);
  s.add_plane({1.f, 0.f, 0.f}, 0.f);
  s.add_plane({-1.f, 0.f, 0.f}, -extent);
  const float h = extent / 2;
  s.add_fixed_box({h, h, h}, {extent / 8, extent / 10, extent / 6}, {0.9238795f, 0.f, 0.f, 0.3826834f});  // 45 deg about z
  return s;
}

// Every pair i < j of non-removed spheres whose surfaces are closer than margin, sorted.
inline std::vector<std::uint64_t> brute_force_pairs(const gpusolve::rbd::BodySet<float>& s, float margin) {
  using namespace gpusolve::rbd;
  std::vector<std::uint64_t> out;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      const Body<float>&a = s[i], &b = s[j];
      if (a.shape != sphere || b.shape != sphere || a.status == removed || b.status == removed) continue;
      float d2 = 0;
      for (int c = 0; c < 3; ++c) d2 += (a.pos[c] - b.pos[c]) * (a.pos[c] - b.pos[c]);
      const float reach = a.shape_param[0] + b.shape_param[0] + margin;
      if (d2 < reach * reach) out.push_back((std::uint64_t(i) << 32) | j);
    }
  return out;
}

}  // namespace rbd_test
