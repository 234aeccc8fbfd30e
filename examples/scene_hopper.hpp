// hopper (thesis 6.1): a square hopper filled with spheres; after a warm-up its outlet opens.
#pragma once

#include <algorithm>
#include <cmath>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "scene_common.hpp"
#include "scene_options.hpp"

namespace scenes {

// Geometry (pe's granular-flow example gives only the counts; the sizes are ours):
// - a square hopper 40 wide inside: four vertical walls above a funnel of four
//   plates inclined at 45 degrees that narrow it from 40 to an outlet 8 wide
//   (4 sphere diameters per side: wide enough that the flow does not jam) over
//   16 of height. The outlet is 20 above the floor plane and is closed by a box
//   (13 x 13 x 1) until the warm-up ends; then that box is removed.
//   All walls are boxes 1 thick, not planes: a plane is an infinite half-space
//   and would cut through the floor the spheres flow onto.
// - the spheres start on a lattice of spacing 2.2 (0.2 apart, so nothing touches
//   at first, as the thesis says), 18 x 18 = 324 per layer with up to 0.05 of
//   jitter, stacked from just above the funnel: 9 857 spheres make 31 layers,
//   68 high. Settled they fill the funnel and about 37 of the shaft; with about
//   2.6 contacts per sphere (walls included) that is the thesis's ~26 000 contacts.
// - warm-up: half of --steps (the thesis's 5 000 of our default 10 000); 12.5 s
//   of simulated time, enough for the top layer to fall 68 and settle.
template <class T>
class Hopper {
 public:
  static SceneDefaults defaults() { return {10000, 9857, 0.0025, 5e-3, 2000, 50, 0.1}; }

  static constexpr double inner_half = 20.0, outlet_half = 4.0, outlet_height = 20.0, wall_half = 0.5;
  static constexpr double funnel_height = inner_half - outlet_half;  // 45 degrees
  static constexpr double spacing = 2.2, jitter = 0.05;

  explicit Hopper(const Options& o) : o_(o), warmup_(std::max(1L, *o.steps / 2)) {}

  void build(gpusolve::rbd::BodySet<T>& set) {
    using V = std::array<T, 3>;
    const long n = *o_.scale;
    const int per_row = static_cast<int>((2 * (inner_half - sphere_radius - jitter)) / spacing) + 1;
    const long layers = (n + per_row * per_row - 1) / (per_row * per_row);
    const double fill_bottom = outlet_height + funnel_height + sphere_radius + 0.5;
    const double top = fill_bottom + layers * spacing + 2.0;

    set.add_plane({0, 0, 1}, 0);
    // Funnel plates. The +x plate runs from the outlet edge (outlet_half, z0) up
    // and out at 45 degrees, its inner face on that line; the other three are it
    // turned about z. Local x runs along the slope, y along the edge, z is the
    // inward normal; the plate is 1.0 longer at the top to meet the shaft walls.
    const double slope = std::sqrt(2.0) * funnel_height + 1.0, s = std::sqrt(0.5);
    for (int k = 0; k < 4; ++k) {
      const double cx = outlet_half + s * 0.5 * slope + s * wall_half;  // mid-slope, moved out by half the thickness
      const double cz = outlet_height + s * 0.5 * slope - s * wall_half;
      const auto q = rotation<T>({0, 0, 1}, k * pi / 2, rotation<T>({0, 1, 0}, -pi / 4));
      const double c = std::cos(k * pi / 2), sn = std::sin(k * pi / 2);
      set.add_fixed_box(V{T(c * cx), T(sn * cx), T(cz)}, V{T(0.5 * slope), T(inner_half + 1.0), T(wall_half)}, q);
    }
    // Vertical shaft walls, from the top of the funnel to above the fill.
    const double wall_bottom = outlet_height + funnel_height, hz = 0.5 * (top - wall_bottom);
    for (int k = 0; k < 4; ++k) {
      const double c = std::cos(k * pi / 2), sn = std::sin(k * pi / 2), d = inner_half + wall_half;
      set.add_fixed_box(V{T(c * d), T(sn * d), T(wall_bottom + hz)}, V{T(wall_half), T(inner_half + 2 * wall_half), T(hz)},
                  rotation<T>({0, 0, 1}, k * pi / 2));
    }
    // The outlet's lid: its top face closes the opening at the outlet height.
    lid_ = set.add_fixed_box(V{0, 0, T(outlet_height - wall_half)}, V{T(outlet_half + 2.5), T(outlet_half + 2.5), T(wall_half)});

    Random rnd(o_.seed);
    const double x0 = -0.5 * (per_row - 1) * spacing;
    long placed = 0;
    for (long l = 0; placed < n; ++l)
      for (int j = 0; j < per_row && placed < n; ++j)
        for (int i = 0; i < per_row && placed < n; ++i, ++placed)
          set.add_sphere(V{T(x0 + i * spacing + rnd.uniform(-jitter, jitter)),
                           T(x0 + j * spacing + rnd.uniform(-jitter, jitter)),
                           T(fill_bottom + l * spacing + rnd.uniform(-jitter, jitter))},
                         T(sphere_radius), sphere_mass(T(sphere_radius)));
  }

  long warmup() const { return warmup_; }
  bool wants_edit(long step) const { return step == warmup_; }
  Changes edit(long, gpusolve::rbd::BodySet<T>&) {
    Changes c;
    c.removed.push_back(lid_);
    return c;
  }

  gpusolve::rbd::io::PovOptions camera() const {
    gpusolve::rbd::io::PovOptions p;
    p.view_dir = {0.9, -1.6, 0.7};
    return p;
  }

 private:
  const Options& o_;
  long warmup_;
  std::size_t lid_ = 0;
};

}  // namespace scenes
