// BoxSlabs: which grid neighbours of a box can give it contact points, read
// from the box's three slabs before the pair's narrow phase runs.
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/rbd/bodies/shape_kind.hpp"
#include "gpusolve/rbd/collision/broad_phase.hpp"

namespace gpusolve::rbd::detail {

// Box i's centre, axes and half extents, loaded once for a walk over its
// neighbours. A neighbour's bounding sphere that lies the margin or more
// outside one of the box's slabs |(y - x) . a_k| <= h_k has no point within the
// margin of the box along that face axis: box_box (pairs/box_box.hpp) stops
// at that axis with no points, and sphere_box measures a true distance at least
// that large, so the pair can be skipped. A cube's bounding sphere reaches
// past its faces by 0.73 of a half extent, so a box in a pile lists
// neighbours its faces cannot meet (docs/detection.md).
template <class T>
struct BoxSlabs {
  bool box = false;  // body i is a box: the test applies
  T x[3] = {}, axis[3][3] = {}, h[3] = {};

  template <class View>
  GPUSOLVE_HD BoxSlabs(const View& b, std::size_t i) {
    if (b.shape[i] != rbd::box) return;
    box = true;
    for (int c = 0; c < 3; ++c) x[c] = b.pos(i, c), h[c] = b.shape_param(i, c);
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) axis[k][c] = b.R(i, 3 * c + k);  // column k of R: axis k in the world
  }

  // Whether the sphere s lies the margin or more outside one of the slabs.
  // A relative 1e-4 keeps rounding from skipping a pair whose narrow phase,
  // summing in another order, finds it just inside the margin.
  GPUSOLVE_HD bool apart(const GridSphere<T>& s, T margin) const {
    if (!box) return false;
    const T d[3] = {s.x[0] - x[0], s.x[1] - x[1], s.x[2] - x[2]};
    for (int k = 0; k < 3; ++k) {
      const T along = std::fabs(axis[k][0] * d[0] + axis[k][1] * d[1] + axis[k][2] * d[2]);
      const T reach = h[k] + s.r + margin;
      if (along - reach >= T(1e-4) * reach) return true;
    }
    return false;
  }
};

// The kinds of neighbour whose narrow phase against a box finds no point
// where BoxSlabs::apart holds (a box or a sphere).
GPUSOLVE_HD inline bool slabs_decide(ShapeKind kind) { return kind == rbd::box || kind == rbd::sphere; }

}  // namespace gpusolve::rbd::detail
