// MergedManifolds: the manifolds of a compound pair's part pairs merged where
// their normals agree, each merged set kept to the corners of the region its
// points span, so a union resting on a face keeps a bounded manifold however
// many parts touch (Jolt reduces a body pair's manifolds so; too many points
// per body pair made stacks of compounds jitter in Box3D and bepu).
#pragma once

#include <cmath>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"

namespace gpusolve::rbd {

template <class T>
struct MergedManifolds {
  // Normals closer than about 3 degrees merge; a point keeps the gap it had
  // along its own normal (off by 1 - cos 3 deg = 0.14% at most).
  static constexpr double same_normal = 0.9986;
  // Sets of one normal kept; a manifold of another normal once they are all
  // taken is not merged.
  static constexpr int max_sets = 4;
  // A set keeps the corners of the convex region its points span and its
  // deepest point, at most this many; a merge that needs more is not made.
  static constexpr int max_set_points = 8;

  struct Set {
    math::Vector3<T> n;
    int count = 0;
    ManifoldPoint<T> points[max_set_points];
  };
  Set set[max_sets];
  int sets = 0;

  // Merges m into a set of its normal (the set keeps its first normal) where
  // their points' corners fit, else starts a set; false where none is left.
  GPUSOLVE_HD bool merge(const Manifold<T>& m) {
    Set one;
    one.n = m.n;
    one.count = m.count;
    for (int k = 0; k < m.count; ++k) one.points[k] = m.points[k];
    for (int s = 0; s < sets; ++s)
      if (merge_into(set[s], one)) return true;
    if (sets == max_sets) return false;
    set[sets++] = one;
    return true;
  }
  // Calls f(manifold) for the sets' points, four at a time, in the order the
  // sets were started, after merging sets that fit together now (two halves
  // of a face, each merged from its parts, make the face).
  template <class F>
  GPUSOLVE_HD void for_each(F&& f) {
    for (int s = 0; s < sets; ++s)
      for (int t = s + 1; t < sets;)
        if (merge_into(set[s], set[t])) {
          for (int k = t + 1; k < sets; ++k) set[k - 1] = set[k];
          --sets;
        } else {
          ++t;
        }
    for (int s = 0; s < sets; ++s)
      for (int first = 0; first < set[s].count; first += max_manifold_points) {
        Manifold<T> m;
        m.n = set[s].n;
        for (int k = first; k < set[s].count && k < first + max_manifold_points; ++k)
          m.add(set[s].points[k].p, set[s].points[k].gap, set[s].points[k].feature);
        f(m);
      }
  }

 private:
  // Merges b into a where their normals agree: a keeps the corners of the
  // convex region both sets' points span in the contact plane and the deepest
  // point, which holds every point the merge drops (each lies within the
  // region, on its rim or inside).
  GPUSOLVE_HD static bool merge_into(Set& a, const Set& b) {
    if (!(math::dot(a.n, b.n) > T(same_normal))) return false;
    ManifoldPoint<T> c[2 * max_set_points];
    int n = 0;
    for (int k = 0; k < a.count; ++k) c[n++] = a.points[k];
    for (int k = 0; k < b.count; ++k) c[n++] = b.points[k];
    int corner[2 * max_set_points];
    T reach = T(0);
    const int corners = region_corners(c, n, a.n, corner, reach);
    int deepest = 0;
    for (int k = 1; k < n; ++k)
      if (c[k].gap < c[deepest].gap) deepest = k;
    T corners_deepest = c[corner[0]].gap;
    for (int k = 1; k < corners; ++k) corners_deepest = std::fmin(corners_deepest, c[corner[k]].gap);
    // An inner point counts only where it lies deeper than every corner (a face's
    // points at one depth, within rounding, keep just the corners).
    const bool deepest_kept = !(c[deepest].gap < corners_deepest - T(1e-3) * reach);
    const int keep = corners + (deepest_kept ? 0 : 1);
    if (keep > max_set_points) return false;
    Set out;
    out.n = a.n;
    for (int k = 0; k < corners; ++k) out.points[out.count++] = c[corner[k]];
    if (!deepest_kept) out.points[out.count++] = c[deepest];
    a = out;
    return true;
  }

  // The corners of the convex region the points c span in the plane normal
  // to `normal` (Andrew's monotone chain; points on an edge, within rounding,
  // are no corners), their indices in order around it; returns how many, and
  // in `reach` the region's size (the farthest point from the first).
  GPUSOLVE_HD static int region_corners(const ManifoldPoint<T>* c, int n, const math::Vector3<T>& normal,
                                        int* corner, T& reach) {
    const T ax = normal[0] < T(0) ? -normal[0] : normal[0], ay = normal[1] < T(0) ? -normal[1] : normal[1];
    const math::Vector3<T> pick = ax < ay ? math::Vector3<T>(T(1), T(0), T(0)) : math::Vector3<T>(T(0), T(1), T(0));
    const math::Vector3<T> u = math::normalize(math::Vector3<T>(pick - math::dot(pick, normal) * normal));
    const math::Vector3<T> v = normal % u;
    T x[2 * max_set_points], y[2 * max_set_points];
    reach = T(0);
    int order[2 * max_set_points];
    for (int k = 0; k < n; ++k) {
      x[k] = math::dot(c[k].p, u), y[k] = math::dot(c[k].p, v);
      order[k] = k;
    }
    for (int k = 1; k < n; ++k) {
      const T dx = x[k] - x[0], dy = y[k] - y[0];
      reach = std::fmax(reach, std::sqrt(dx * dx + dy * dy));
    }
    for (int k = 1; k < n; ++k)  // insertion sort by (x, y) of at most 16
      for (int j = k; j > 0; --j) {
        const int p = order[j], q = order[j - 1];
        if (!(x[p] < x[q] || (x[p] == x[q] && y[p] < y[q]))) break;
        order[j] = q, order[j - 1] = p;
      }
    const T slack = T(1e-3) * reach;  // a turn smaller than this, times the edge, is no corner
    const auto turns_left = [&](int o, int a, int b) {
      const T ex = x[a] - x[o], ey = y[a] - y[o], fx = x[b] - x[o], fy = y[b] - y[o];
      return ex * fy - ey * fx > slack * std::sqrt(fx * fx + fy * fy);
    };
    int hull[4 * max_set_points], h = 0;
    for (int k = 0; k < n; ++k) {  // the lower chain
      while (h >= 2 && !turns_left(hull[h - 2], hull[h - 1], order[k])) --h;
      hull[h++] = order[k];
    }
    for (int k = n - 2, lower = h + 1; k >= 0; --k) {  // the upper chain
      while (h >= lower && !turns_left(hull[h - 2], hull[h - 1], order[k])) --h;
      hull[h++] = order[k];
    }
    const int corners = h > 1 ? h - 1 : h;  // the last repeats the first
    for (int k = 0; k < corners; ++k) corner[k] = hull[k];
    return corners;
  }
};

}  // namespace gpusolve::rbd
