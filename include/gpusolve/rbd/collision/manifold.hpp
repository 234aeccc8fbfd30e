// Manifold: the contact points one shape pair produces, up to four, sharing a
// normal; each point carries a feature id so warm starting can match it.
#pragma once

#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd {

// A box face against a face is clipped to at most this many points (the
// deepest and the ones spanning the largest area, as Jolt and PhysX keep).
inline constexpr int max_manifold_points = 4;

// The feature id of a contact that stands in for a point the narrow phase no
// longer finds (collision detection's write pass); it matches no real point.
inline constexpr std::uint32_t inert_feature = ~std::uint32_t(0);

// One contact point: p lies midway between the two surfaces, gap is their
// distance along the manifold's normal (negative where they overlap), and
// feature names the features that made it (a vertex, an edge crossing), the
// same from step to step while the same features touch.
template <class T>
struct ManifoldPoint {
  math::Vector3<T> p;
  T gap;
  std::uint32_t feature;
};

// The points of body a against body b; n is a unit vector from b to a.
template <class T>
struct Manifold {
  math::Vector3<T> n;
  int count = 0;
  ManifoldPoint<T> points[max_manifold_points];

  // Appends a point (ignored past max_manifold_points).
  GPUSOLVE_HD void add(const math::Vector3<T>& p, T gap, std::uint32_t feature) {
    if (count < max_manifold_points) points[count++] = {p, gap, feature};
  }
  // The same contact seen from the other body: the normal turns, nothing else.
  GPUSOLVE_HD Manifold flipped() const {
    Manifold m = *this;
    m.n = -n;
    return m;
  }
};

// The manifold of one point q on b's surface, normal n from b to a, gap along
// n: the point midway lies at q + n gap / 2.
template <class T>
GPUSOLVE_HD Manifold<T> one_point(const math::Vector3<T>& q, const math::Vector3<T>& n, T gap,
                                  std::uint32_t feature = 0) {
  Manifold<T> m;
  m.n = n;
  m.add(math::Vector3<T>(q + (gap / 2) * n), gap, feature);
  return m;
}

// m without its points whose gap is not below the margin.
template <class T>
GPUSOLVE_HD Manifold<T> within_margin(const Manifold<T>& m, T margin) {
  Manifold<T> kept;
  kept.n = m.n;
  for (int k = 0; k < m.count; ++k)
    if (m.points[k].gap < margin) kept.add(m.points[k].p, m.points[k].gap, m.points[k].feature);
  return kept;
}

}  // namespace gpusolve::rbd
