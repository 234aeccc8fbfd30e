// MergedManifolds: the manifolds of a compound pair's part pairs merged where
// their normals agree, each merged set kept to four points, so a union
// resting on a face keeps a bounded manifold however many parts touch (Jolt
// reduces a body pair's manifolds so; too many points per body pair made
// stacks of compounds jitter in Box3D and bepu).
#pragma once

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"
#include "gpusolve/rbd/collision/pairs/reduce_points.hpp"

namespace gpusolve::rbd {

template <class T>
struct MergedManifolds {
  // Normals closer than about 3 degrees merge; a point keeps the gap it had
  // along its own normal (off by 1 - cos 3 deg = 0.14% at most).
  static constexpr double same_normal = 0.9986;
  // Sets of one normal kept; a manifold of another normal once they are all
  // taken is not merged.
  static constexpr int max_sets = 4;

  Manifold<T> set[max_sets];
  int sets = 0;

  // Merges m into the set of its normal (the set keeps its first normal), or
  // starts a set; false where m found no set.
  GPUSOLVE_HD bool merge(const Manifold<T>& m) {
    for (int s = 0; s < sets; ++s) {
      if (!(math::dot(set[s].n, m.n) > T(same_normal))) continue;
      ManifoldPoint<T> points[2 * max_manifold_points];
      int n = 0;
      for (int k = 0; k < set[s].count; ++k) points[n++] = set[s].points[k];
      for (int k = 0; k < m.count; ++k) points[n++] = m.points[k];
      set[s] = reduce_to_four(points, n, set[s].n);
      return true;
    }
    if (sets == max_sets) return false;
    set[sets++] = m;
    return true;
  }
  // Calls f(manifold) for each set, in the order they were started.
  template <class F>
  GPUSOLVE_HD void for_each(F&& f) const {
    for (int s = 0; s < sets; ++s) f(set[s]);
  }
};

}  // namespace gpusolve::rbd
