// blocks: a pyramid of boxes, and boxes, capsules, spheres and compounds
// dropped onto it (pe's primitives and unions together; its GPU integration
// moved boxes, thesis Fig. 11).
#pragma once

#include <cmath>
#include <vector>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/bodies/mass_properties.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "scene_common.hpp"
#include "scene_options.hpp"

namespace scenes {

// A pyramid of 6 rows of cubes (half extent 1, 21 of them) stands on the floor
// in an open box of planes 14 to each side. Above it `scale` bodies wait on a
// lattice of spacing 3.5, turned at random, a box (half extents 1, 0.6, 0.4),
// a capsule (radius 0.5, half length 1), a sphere (radius 1) and a compound
// (a clump of three spheres of radius 0.6, or a hammer: a capsule handle with
// a box head) in turn, all of density 1; they fall onto the pyramid and scatter around it.
template <class T>
class Blocks {
 public:
  static SceneDefaults defaults() { return {2000, 48, 0.0025, 5e-3, 2000, 50, 0.5}; }

  explicit Blocks(const Options& o) : o_(o) {}

  void build(gpusolve::rbd::BodySet<T>& set) {
    using gpusolve::rbd::solid_box;
    using gpusolve::rbd::solid_capsule;
    using gpusolve::rbd::solid_compound;
    constexpr double half = 14.0, spacing = 3.5;
    set.add_plane({0, 0, 1}, 0);
    set.add_plane({1, 0, 0}, T(-half));
    set.add_plane({-1, 0, 0}, T(-half));
    set.add_plane({0, 1, 0}, T(-half));
    set.add_plane({0, -1, 0}, T(-half));
    const std::array<T, 3> cube{1, 1, 1}, brick{T(1), T(0.6), T(0.4)};
    for (int row = 0; row < 6; ++row)
      for (int k = 0; k + row < 6; ++k)
        set.add_box({T((k - 0.5 * (5 - row)) * 2.02), 0, T(1 + 2 * row)}, cube, solid_box(cube, T(1)).volume);
    using Part = gpusolve::rbd::Part<T>;
    using gpusolve::rbd::capsule, gpusolve::rbd::box, gpusolve::rbd::sphere;
    const std::vector<Part> clump = {{sphere, {T(0.6), 0, 0, 0}, {T(0.55), 0, 0}, {1, 0, 0, 0}},
                                     {sphere, {T(0.6), 0, 0, 0}, {T(-0.28), T(0.48), 0}, {1, 0, 0, 0}},
                                     {sphere, {T(0.6), 0, 0, 0}, {T(-0.28), T(-0.48), 0}, {1, 0, 0, 0}}};
    const std::vector<Part> hammer = {{capsule, {T(0.3), T(1), 0, 0}, {0, 0, 0}, {1, 0, 0, 0}},
                                      {box, {T(0.4), T(0.7), T(0.4), 0}, {T(1.5), 0, 0}, {1, 0, 0, 0}}};
    // Each compound kind stored once, shared by every body of it (a clump template).
    const auto clump_type = set.add_compound_type(clump, solid_compound(clump, T(1)).volume);
    const auto hammer_type = set.add_compound_type(hammer, solid_compound(hammer, T(1)).volume);
    Random rnd(o_.seed);
    const long n = *o_.scale;
    const int side = 5;
    for (long i = 0; i < n; ++i) {
      const std::array<T, 3> x{T((i % side - 0.5 * (side - 1)) * spacing), T((i / side % side - 0.5 * (side - 1)) * spacing),
                               T(16 + (i / (side * side)) * spacing)};
      const double ax = rnd.uniform(-1, 1), ay = rnd.uniform(-1, 1), len = std::sqrt(ax * ax + ay * ay + 1);
      const auto q = rotation<T>({T(ax / len), T(ay / len), T(1 / len)}, rnd.uniform(0, 2 * pi));
      if (i % 4 == 0) set.add_box(x, brick, solid_box(brick, T(1)).volume, q);
      if (i % 4 == 1) set.add_capsule(x, T(0.5), T(1), solid_capsule(T(0.5), T(1), T(1)).volume, q);
      if (i % 4 == 2) set.add_sphere(x, T(sphere_radius), sphere_mass(T(sphere_radius)));
      if (i % 4 == 3) set.add_compound(x, i % 8 == 3 ? clump_type : hammer_type, q);
    }
  }

  bool wants_edit(long) const { return false; }
  Changes edit(long, gpusolve::rbd::BodySet<T>&) { return {}; }

  gpusolve::rbd::io::PovOptions camera() const {
    gpusolve::rbd::io::PovOptions p;
    p.view_dir = {0.7, -1.8, 0.9};
    return p;
  }

 private:
  const Options& o_;
};

}  // namespace scenes
