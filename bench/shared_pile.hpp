// The atlas's scenes as BodySets: the shared sphere and cube piles of docs/piles.md
// (the scenes peer engines are measured on), a mixed pile, a column of spheres
// of alternating mass, a pile of sphere clumps, one of 4-part unions, a box pyramid and a box stack.
#pragma once

#include <cmath>
#include <array>
#include <cstddef>
#include <random>
#include <vector>

#include "gpusolve/rbd/bodies/body_set.hpp"

namespace gpusolve::bench {

// N spheres (radius 1, mass 1) on a jittered cubic lattice of spacing 2.1 in an
// open box of planes, exactly as the shared pile specification prescribes: side
// L = ceil(cbrt N), sphere i at lattice (i mod L, (i / L) mod L, i / L^2) plus
// jitters (jx, jy, jz) from std::mt19937(1) and uniform_real_distribution(-0.05,
// 0.05), the floor z = 0 and walls x, y = +-h with h = (L s + 0.2) / 2.
// The open-top box of planes around a lattice of side L and spacing s: the
// floor z = 0 and the walls x, y = +-h, h = (L s + 0.2) / 2.
template <class T>
void add_open_box(rbd::BodySet<T>& set, std::size_t L, double s) {
  const T h = T((double(L) * s + 0.2) / 2);
  set.add_plane({0, 0, 1}, 0);
  set.add_plane({1, 0, 0}, -h);  // n.x = d: the wall x = -h, solid below
  set.add_plane({-1, 0, 0}, -h);
  set.add_plane({0, 1, 0}, -h);
  set.add_plane({0, -1, 0}, -h);
}

// Calls body(i, centre) for the n sites of docs/piles.md's jittered cubic lattice of
// spacing s, lowest layer at z0: side L = ceil(cbrt n), site i at (i mod L,
// (i / L) mod L, i / L^2) plus jitters (jx, jy, jz) from std::mt19937(1) and
// uniform_real_distribution(-0.05, 0.05); returns L.
template <class F>
std::size_t jittered_lattice(std::size_t n, double s, double z0, F&& body) {
  const std::size_t L = std::size_t(std::ceil(std::cbrt(double(n)) - 1e-9));
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const double c0 = -(double(L) - 1) * s / 2;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t x = i % L, y = (i / L) % L, z = i / (L * L);
    const double jx = jitter(gen), jy = jitter(gen), jz = jitter(gen);
    body(i, std::array<double, 3>{c0 + x * s + jx, c0 + y * s + jy, z0 + z * s + jz});
  }
  return L;
}

// The shared sphere pile: N spheres (radius 1, mass 1), spacing 2.1, z0 = 1.1.
template <class T>
rbd::BodySet<T> shared_pile(std::size_t n) {
  rbd::BodySet<T> set;
  const std::size_t L = jittered_lattice(n, 2.1, 1.1, [&](std::size_t, const std::array<double, 3>& c) {
    set.add_sphere({T(c[0]), T(c[1]), T(c[2])}, T(1), T(1));
  });
  add_open_box(set, L, 2.1);
  return set;
}

// Part `part` of `parts` of the shared sphere pile, for ranks that each add
// their own: the planes on part 0, first, and the spheres of the lattice
// sites [n part / parts, n (part + 1) / parts) with their jitters as above.
// Numbered part by part, the parts hold the pile with its planes first.
template <class T>
rbd::BodySet<T> shared_pile_part(std::size_t n, std::size_t part, std::size_t parts) {
  rbd::BodySet<T> set;
  const std::size_t L = std::size_t(std::ceil(std::cbrt(double(n)) - 1e-9));
  if (part == 0) add_open_box(set, L, 2.1);
  const std::size_t lo = n * part / parts, hi = n * (part + 1) / parts;
  jittered_lattice(n, 2.1, 1.1, [&](std::size_t i, const std::array<double, 3>& c) {
    if (i >= lo && i < hi) set.add_sphere({T(c[0]), T(c[1]), T(c[2])}, T(1), T(1));
  });
  return set;
}

// A random orientation: four draws of `normal` (0, 1) on `gen`, normalised.
template <class T>
std::array<T, 4> random_turn(std::mt19937& gen, std::normal_distribution<double>& normal) {
  double q[4], len = 0;
  for (double& x : q) x = normal(gen), len += x * x;
  len = std::sqrt(len);
  return {T(q[0] / len), T(q[1] / len), T(q[2] / len), T(q[3] / len)};
}

// Random orientations as docs/piles.md draws them: random_turn on std::mt19937(2).
class RandomTurns {
 public:
  template <class T>
  std::array<T, 4> next() {
    return random_turn<T>(gen_, normal_);
  }

 private:
  std::mt19937 gen_{2};
  std::normal_distribution<double> normal_{0.0, 1.0};
};

// The shared cube pile: N cubes (half extent 1, mass 1), spacing 3.6, z0 = 1.8,
// each turned at random.
template <class T>
rbd::BodySet<T> cube_pile(std::size_t n) {
  rbd::BodySet<T> set;
  RandomTurns turns;
  const std::size_t L = jittered_lattice(n, 3.6, 1.8, [&](std::size_t, const std::array<double, 3>& c) {
    set.add_box({T(c[0]), T(c[1]), T(c[2])}, {T(1), T(1), T(1)}, T(1), turns.next<T>());
  });
  add_open_box(set, L, 3.6);
  return set;
}

// The mixed pile: the cube pile's lattice filled in turn with a sphere
// (radius 1), a box (half extents 1, 0.7, 0.5), a capsule (radius 0.5, half
// length 0.9) and a clump of three spheres (radius 0.6, 0.55 from its
// centre), all of mass 1 and turned at random.
template <class T>
rbd::BodySet<T> mixed_pile(std::size_t n) {
  rbd::BodySet<T> set;
  RandomTurns turns;
  std::vector<rbd::Part<T>> clump;
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * 3.14159265358979 * k / 3;
    clump.push_back({rbd::sphere, {T(0.6), 0, 0, 0}, {T(0.55 * std::cos(a)), T(0.55 * std::sin(a)), T(0)}, {1, 0, 0, 0}});
  }
  const rbd::CompoundType<T> clump_type = set.add_compound_type(clump, T(1));
  const std::size_t L = jittered_lattice(n, 3.6, 1.8, [&](std::size_t i, const std::array<double, 3>& c) {
    const std::array<T, 3> x{T(c[0]), T(c[1]), T(c[2])};
    const std::array<T, 4> q = turns.next<T>();
    if (i % 4 == 0) set.add_sphere(x, T(1), T(1));
    if (i % 4 == 1) set.add_box(x, {T(1), T(0.7), T(0.5)}, T(1), q);
    if (i % 4 == 2) set.add_capsule(x, T(0.5), T(0.9), T(1), q);
    if (i % 4 == 3) set.add_compound(x, clump_type, q);
  });
  add_open_box(set, L, 3.6);
  return set;
}

// The clump pile (issue 36): N clumps of three spheres of radius 1 whose
// centres lie on a line 1.2 apart, one compound type of mass 3 (its inertia
// summed over the spheres, the overlaps counted twice), on the jittered
// lattice at spacing 4.5 (a clump reaches 2.2 from its centre), z0 = 2.3,
// turned at random, in the open box of planes.
template <class T>
rbd::BodySet<T> clump_pile(std::size_t n) {
  rbd::BodySet<T> set;
  RandomTurns turns;
  std::vector<rbd::Part<T>> line;
  for (int k = -1; k <= 1; ++k) line.push_back({rbd::sphere, {T(1), 0, 0, 0}, {T(1.2 * k), 0, 0}, {1, 0, 0, 0}});
  const rbd::CompoundType<T> type = set.add_compound_type(line, T(3));
  const std::size_t L = jittered_lattice(n, 4.5, 2.3, [&](std::size_t, const std::array<double, 3>& c) {
    set.add_compound({T(c[0]), T(c[1]), T(c[2])}, type, turns.next<T>());
  });
  add_open_box(set, L, 4.5);
  return set;
}

// The union pile (issue 36): N unions of four parts on the clump pile's
// lattice, turned at random, of two types in turn, both of mass 4: an L of four
// cubes (half extent 0.5; three in a row, one on the first), and a hammer of a
// capsule handle (radius 0.3, half length 1), a box head (half extents 0.3,
// 0.7, 0.3) and a sphere (radius 0.4) at each end of the head; each reaches
// less than 2.25 from its centre of mass.
template <class T>
rbd::BodySet<T> union_pile(std::size_t n) {
  rbd::BodySet<T> set;
  RandomTurns turns;
  const std::array<T, 4> unturned{1, 0, 0, 0};
  const std::array<T, 4> cube{T(0.5), T(0.5), T(0.5), 0};
  const rbd::CompoundType<T> l = set.add_compound_type({{rbd::box, cube, {T(-1), 0, 0}, unturned},
                                                        {rbd::box, cube, {0, 0, 0}, unturned},
                                                        {rbd::box, cube, {T(1), 0, 0}, unturned},
                                                        {rbd::box, cube, {T(-1), 0, T(1)}, unturned}},
                                                       T(4));
  const rbd::CompoundType<T> hammer =
      set.add_compound_type({{rbd::capsule, {T(0.3), T(1.0), 0, 0}, {T(-0.2), 0, 0}, unturned},
                             {rbd::box, {T(0.3), T(0.7), T(0.3), 0}, {T(1.2), 0, 0}, unturned},
                             {rbd::sphere, {T(0.4), 0, 0, 0}, {T(1.2), T(0.9), 0}, unturned},
                             {rbd::sphere, {T(0.4), 0, 0, 0}, {T(1.2), T(-0.9), 0}, unturned}},
                            T(4));
  const std::size_t L = jittered_lattice(n, 4.5, 2.3, [&](std::size_t i, const std::array<double, 3>& c) {
    set.add_compound({T(c[0]), T(c[1]), T(c[2])}, i % 2 == 0 ? l : hammer, turns.next<T>());
  });
  add_open_box(set, L, 4.5);
  return set;
}

// Adds a pyramid of unit cubes (half extent 0.5, mass 1) standing on the
// floor at (x0, y0): `layers` rows in the x-z plane, the bottom one `layers`
// long, each row centred on the one below (210 boxes for 20 layers), 0.01 apart.
template <class T>
void add_box_pyramid(rbd::BodySet<T>& set, std::size_t layers, double x0, double y0) {
  for (std::size_t l = 0; l < layers; ++l)
    for (std::size_t k = 0; k + l < layers; ++k)
      set.add_box({T(x0 + (double(k) - double(layers - l - 1) / 2) * 1.01), T(y0), T(0.5 + 1.0 * double(l))},
                  {T(0.5), T(0.5), T(0.5)}, T(1));
}

// One pyramid of `layers` on the floor (add_box_pyramid).
template <class T>
rbd::BodySet<T> box_pyramid(std::size_t layers) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  add_box_pyramid(set, layers, 0, 0);
  return set;
}

// A field of 20 pyramids of `layers` (4 200 boxes for 20 layers, the size of
// NVIDIA Newton's pyramid example): 4 rows along x of 5 pyramids along y, 2
// apart in y and a base plus 2 apart in x.
template <class T>
rbd::BodySet<T> pyramid_field(std::size_t layers) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  const double pitch = double(layers) * 1.01 + 2;
  for (int row = 0; row < 4; ++row)
    for (int k = 0; k < 5; ++k) add_box_pyramid(set, layers, (row - 1.5) * pitch, (k - 2) * 2.0);
  return set;
}

// A tower of `count` thin slabs (3 x 1 x 0.2, density 1, as Kapla blocks) on
// the floor, laid in pairs: a layer's two slabs lie side by side 1.5 apart,
// along x in even layers and along y in odd ones.
template <class T>
rbd::BodySet<T> slab_tower(std::size_t count) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  const double s = std::sqrt(0.5);
  const std::array<T, 4> along_y{T(s), 0, 0, T(s)};  // a quarter turn about z
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t layer = k / 2;
    const double side = k % 2 == 0 ? -0.75 : 0.75, z = 0.1 + 0.2 * double(layer);
    if (layer % 2 == 0)
      set.add_box({0, T(side), T(z)}, {T(1.5), T(0.5), T(0.1)}, T(0.6));
    else
      set.add_box({T(side), 0, T(z)}, {T(1.5), T(0.5), T(0.1)}, T(0.6), along_y);
  }
  return set;
}

// A rough floor: 8 x 8 fixed cubes (half extent 1) 2.5 apart, turned at
// random, and 16 cubes (mass 1) 4 above them, 5 apart, turned at random,
// thrown down at `speed` m/s (and sideways up to half that), spinning at up to
// about `spin` rad/s about each axis. Random draws from std::mt19937 seeded `seed`.
template <class T>
rbd::BodySet<T> rough_floor(unsigned seed, double speed = 3, double spin = 3) {
  rbd::BodySet<T> set;
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal(0, 1);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  const auto turn = [&] { return random_turn<T>(gen, normal); };
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) set.add_fixed_box({T(i * 2.5), T(j * 2.5), 0}, {1, 1, 1}, turn());
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const std::array<T, 3> x{T(1.25 + i * 5.0 + jitter(gen)), T(1.25 + j * 5.0 + jitter(gen)), 4};
      const std::size_t k = set.add_box(x, {1, 1, 1}, 1, turn());
      set[k].v = {T(speed * jitter(gen)), T(speed * jitter(gen)), T(-speed)};
      set[k].w = {T(spin * normal(gen)), T(spin * normal(gen)), T(spin * normal(gen))};
    }
  return set;
}

// `count` unit cubes stacked on the floor, exactly aligned.
template <class T>
rbd::BodySet<T> box_stack(std::size_t count) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  for (std::size_t k = 0; k < count; ++k) set.add_box({0, 0, T(0.5 + double(k))}, {T(0.5), T(0.5), T(0.5)}, T(1));
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
