// well (thesis 6.1, Fig. 16): spheres poured at random into a round well of 150 fixed boxes on a plane.
#pragma once

#include <algorithm>
#include <cmath>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "scene_common.hpp"
#include "scene_options.hpp"

namespace scenes {

// Geometry (the thesis gives only the counts; the sizes are ours):
// - the well: 5 rings of 30 boxes; each box 1 thick (radial), 2 high and one
//   30th of the ring long (2 pi 12 / 30 = 2.51), centres on a circle of radius
//   12, so the shaft is 23 wide inside and 10 high. Odd rings are turned by half
//   a box, like bricks.
// - insertion: spheres of radius 1 at random in a disc of radius 8 (well inside
//   the shaft) between heights 30 and 40, never overlapping a sphere already
//   there (a placement is retried up to 50 times, then left to the next step).
//   The count follows a straight line from 0 at step 0 to --scale at the
//   insertion stop (90% of --steps: the thesis's 18 000 of 20 000), so the
//   thesis's 3 900 spheres arrive one every 4.6 steps. They fall about 25
//   (about 2.3 s, 900 steps) before they reach the floor.
// - the shaft holds about 415 * 10 * 0.6 / 4.19 = 600 spheres when packed; the
//   rest heaps up above and overflows onto the plane, as in Fig. 16 (c).
template <class T>
class Well {
 public:
  static SceneDefaults defaults() { return {20000, 3900, 0.0025, 5e-3, 2000, 50, 0.1}; }

  static constexpr int rings = 5, boxes_per_ring = 30;
  static constexpr double ring_radius = 12.0, wall_half = 0.5, level_half = 1.0;
  static constexpr double insert_radius = 8.0, insert_low = 30.0, insert_high = 40.0;
  static constexpr int placement_tries = 50;

  explicit Well(const Options& o)
      : o_(o), stop_(std::max(1L, std::lround(0.9 * *o.steps))), rnd_(o.seed) {}

  void build(gpusolve::rbd::BodySet<T>& set) {
    set.add_plane({0, 0, 1}, 0);
    const double half_length = pi * ring_radius / boxes_per_ring;
    for (int level = 0; level < rings; ++level)
      for (int k = 0; k < boxes_per_ring; ++k) {
        const double phi = 2 * pi * (k + 0.5 * (level % 2)) / boxes_per_ring;
        // Local x is radial, y tangential, z up.
        set.add_fixed_box({T(ring_radius * std::cos(phi)), T(ring_radius * std::sin(phi)),
                     T(level_half * (2 * level + 1))},
                    {T(wall_half), T(half_length), T(level_half)}, rotation<T>({0, 0, 1}, phi));
      }
    first_sphere_ = set.size();
  }

  // Spheres the schedule wants in the scene before `step` runs.
  long target(long step) const {
    if (step >= stop_) return *o_.scale;
    return std::min<long>(*o_.scale, (*o_.scale * (step + 1) + stop_ - 1) / stop_);
  }
  bool wants_edit(long step) const { return inserted_ < target(step); }
  long inserted() const { return inserted_; }
  long insertion_stop() const { return stop_; }

  Changes edit(long step, gpusolve::rbd::BodySet<T>& set) {
    Changes c;
    const double r = sphere_radius, min_d2 = (2 * r + 0.01) * (2 * r + 0.01);
    for (long want = target(step) - inserted_; want > 0; --want) {
      bool placed = false;
      for (int t = 0; t < placement_tries && !placed; ++t) {
        const double a = rnd_.uniform(0, 2 * pi), d = insert_radius * std::sqrt(rnd_.uniform(0, 1));
        const std::array<T, 3> p{T(d * std::cos(a)), T(d * std::sin(a)), T(rnd_.uniform(insert_low, insert_high))};
        placed = true;
        for (std::size_t i = first_sphere_; i < set.size() && placed; ++i) {
          const auto& b = set[i];
          // Only spheres that reach into the insertion band can overlap.
          if (b.status == gpusolve::rbd::removed || b.pos[2] < insert_low - 2 * r) continue;
          const double dx = b.pos[0] - p[0], dy = b.pos[1] - p[1], dz = b.pos[2] - p[2];
          placed = dx * dx + dy * dy + dz * dz >= min_d2;
        }
        if (placed) c.added.push_back(set.add_sphere(p, T(r), sphere_mass(T(r))));
      }
      if (!placed) break;  // the band is crowded: try again next step
      ++inserted_;
    }
    return c;
  }

  // A fixed camera on the well (not fitted to the spheres, which start high and
  // may scatter): frames of one run line up as an animation.
  gpusolve::rbd::io::PovOptions camera() const {
    gpusolve::rbd::io::PovOptions p;
    p.auto_camera = false;
    p.look_at = {0, 0, 12};
    p.camera = {35, -85, 75};
    return p;
  }

 private:
  const Options& o_;
  long stop_;
  Random rnd_;
  long inserted_ = 0;
  std::size_t first_sphere_ = 0;
};

}  // namespace scenes
