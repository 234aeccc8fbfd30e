// ballpark (thesis 5.2, Fig. 13): a block of 7x7x7 slightly misaligned spheres falling in a closed box.
#pragma once

#include <algorithm>
#include <cmath>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/io/povray_writer.hpp"
#include "scene_common.hpp"
#include "scene_options.hpp"

namespace scenes {

// The block is k x k x k spheres, k = ceil(cbrt(scale)) (7 for the default 343;
// filled in order, so a scale that is not a cube leaves the top layer short),
// on a lattice of spacing 2.5 with each sphere moved by up to 0.1 along every
// axis: the misalignment that makes the block collapse sideways when it lands
// instead of stacking. Its bottom starts 10 above the floor (about 1.4 s of fall,
// 570 steps), and the box leaves 4 of room on each side of the block. Fig. 13
// shows 1 000 steps: the fall, the impact and the spreading.
template <class T>
class Ballpark {
 public:
  static SceneDefaults defaults() { return {1000, 343, 0.0025, 5e-3, 2000, 50, 0.1}; }

  explicit Ballpark(const Options& o) : o_(o) {}

  void build(gpusolve::rbd::BodySet<T>& set) {
    const long n = *o_.scale;
    const int k = static_cast<int>(std::ceil(std::cbrt(double(n)) - 1e-9));
    constexpr double spacing = 2.5, jitter = 0.1, drop = 10.0;
    const double half = 0.5 * (k - 1) * spacing + sphere_radius + 4.0;
    const double height = drop + k * spacing + 10.0;
    // Six planes whose solid sides face outwards (normal into the box).
    set.add_plane({0, 0, 1}, 0);
    set.add_plane({0, 0, -1}, T(-height));
    set.add_plane({1, 0, 0}, T(-half));
    set.add_plane({-1, 0, 0}, T(-half));
    set.add_plane({0, 1, 0}, T(-half));
    set.add_plane({0, -1, 0}, T(-half));
    Random rnd(o_.seed);
    long placed = 0;
    for (int z = 0; z < k && placed < n; ++z)
      for (int y = 0; y < k && placed < n; ++y)
        for (int x = 0; x < k && placed < n; ++x, ++placed) {
          auto coord = [&](int i) { return (i - 0.5 * (k - 1)) * spacing + rnd.uniform(-jitter, jitter); };
          const T px = T(coord(x)), py = T(coord(y));
          const T pz = T(drop + sphere_radius + z * spacing + rnd.uniform(-jitter, jitter));
          set.add_sphere({px, py, pz}, T(sphere_radius), sphere_mass(T(sphere_radius)));
        }
  }

  bool wants_edit(long) const { return false; }
  Changes edit(long, gpusolve::rbd::BodySet<T>&) { return {}; }

  // Seen from the front and above, so that the open side faces the camera.
  gpusolve::rbd::io::PovOptions camera() const {
    gpusolve::rbd::io::PovOptions p;
    p.view_dir = {0.6, -1.8, 1.2};
    return p;
  }

 private:
  const Options& o_;
};

}  // namespace scenes
