// The rbd benchmarks' contact set: a settled-looking dense pile of spheres on a plane, sized to a contact count.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "gpusolve/rbd/contact_models/contact_model.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"

namespace gpusolve::bench {

// Geometry of the pile (radius 1, mass 1, the thesis's spheres). Neighbours on
// the lattice overlap by 1% of the radius and the bottom layer sinks 1% into the
// floor: what a pile looks like after it settled under an iterative solver. The
// jitter (0.1% of the radius per coordinate) breaks the lattice's symmetry but
// can change a pair distance by at most 0.35% of the radius, so every lattice
// neighbour stays in contact and the count is a property of the shape alone.
struct PileGeometry {
  double radius = 1.0;
  double overlap = 0.01;   // of the radius, between neighbours and into the floor
  double jitter = 0.001;   // of the radius, uniform per coordinate
  double slope = 0.5;      // each layer is inset by slope * layer height on every side
  double velocity = 0.01;  // random velocity and spin amplitude (m/s, rad/s)
  double dt = 0.0025;      // gravity's velocity change over one step is added to v_z
};

// Spheres on a jittered face-centred cubic lattice (close-packed layers stacked
// ABC) filling a heap whose base is a square of `side` sphere spacings, with
// side / 3 layers, resting on the plane z = 0 (the last body). Velocities are
// small, random and non-zero, plus one step of gravity, as on entry to a solve.
template <class T>
rbd::BodySet<T> make_pile(double side, const PileGeometry& g = {}, std::uint32_t seed = 1) {
  const double r = g.radius;
  const double d = 2 * r - g.overlap * r;  // centre spacing
  const double dy = d * std::sqrt(3.0) / 2;  // row spacing within a layer
  const double dz = d * std::sqrt(2.0 / 3.0);  // layer spacing
  const double width = side * d;
  const int layers = std::max(1, int(std::lround(side / 3)));
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  rbd::BodySet<T> set;
  for (int k = 0; k < layers; ++k) {
    const double inset = g.slope * k * dz;
    const double sx = (k % 3) * d / 2, sy = (k % 3) * dy / 3;  // ABC stacking
    const double z = r - g.overlap * r + k * dz;
    for (int j = -1; j * dy <= width + dy; ++j)
      for (int i = -1; i * d <= width + d; ++i) {
        const double x = i * d + (j & 1) * d / 2 + sx, y = j * dy + sy;
        if (x < inset || x > width - inset || y < inset || y > width - inset) continue;
        const auto jit = [&] { return T(g.jitter * r * unit(gen)); };
        const std::size_t id = set.add_sphere({T(x) + jit(), T(y) + jit(), T(z) + jit()}, T(r), T(1));
        auto& b = set[id];
        for (int c = 0; c < 3; ++c) {
          b.v[c] = T(g.velocity * unit(gen));
          b.w[c] = T(g.velocity * unit(gen));
        }
        b.v[2] += T(-9.81 * g.dt);
      }
  }
  set.add_plane({0, 0, 1}, 0);
  return set;
}

// The number of contacts collision detection finds in a pile (margin 0).
template <class Device, class T>
std::size_t count_contacts(rbd::BodySet<T>& set) {
  rbd::BodyManager<Device, T> manager(set);
  manager.syncDeviceFull();
  rbd::Contacts<Device, T, rbd::Frictionless> contacts;
  rbd::CollisionDetection<Device, T> detection;
  return detection.detect(manager.device(), contacts, T(0));
}

// The pile whose contact count is closest to `target`: bisection on the side
// (the count grows monotonically with it, up to lattice steps).
template <class Device, class T>
rbd::BodySet<T> pile_with_contacts(std::size_t target, const PileGeometry& g = {}) {
  double lo = 1, hi = 4;
  for (;;) {  // bracket the target
    rbd::BodySet<T> set = make_pile<T>(hi, g);
    if (count_contacts<Device>(set) >= target) break;
    lo = hi, hi *= 2;
  }
  double best = hi;
  std::size_t best_err = ~std::size_t(0);
  for (int step = 0; step < 24 && hi - lo > 1e-3; ++step) {
    const double mid = 0.5 * (lo + hi);
    rbd::BodySet<T> set = make_pile<T>(mid, g);
    const std::size_t n = count_contacts<Device>(set);
    const std::size_t err = n > target ? n - target : target - n;
    if (err < best_err) best_err = err, best = mid;
    if (err * 200 < target) break;  // within 0.5%
    (n < target ? lo : hi) = mid;
  }
  return make_pile<T>(best, g);
}

}  // namespace gpusolve::bench
