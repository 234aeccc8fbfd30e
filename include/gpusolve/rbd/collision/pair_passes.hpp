// The narrow phase one thread per candidate pair: a body's walk lists the
// partners whose bounds come within the margin, and each pair's manifolds are
// then counted and written by a thread of its own, so a box pile's costly
// shape pairs spread over the GPU instead of queueing behind one thread per
// body (docs/detection.md has the measurements).
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/materials.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"
#include "gpusolve/rbd/collision/kept_partners.hpp"
#include "gpusolve/rbd/collision/manifold.hpp"

namespace gpusolve::rbd::detail {

// Writes manifold points as contacts of the pair (i, j), with the friction,
// restitution and rolling and spinning resistance of the bodies' materials, and inert contacts where a pass
// finds fewer points than its count said.
template <class Walk, class ContactView, class T>
struct PointWriter {
  Walk walk;
  ContactView contacts;
  ContactDefaults<T> defaults;

  GPUSOLVE_HD void write(std::uint32_t o, std::size_t i, std::uint32_t j, const Manifold<T>& m, int k) const {
    const auto& b = walk.b;
    const ManifoldPoint<T>& q = m.points[k];
    const math::Vector3<T> ra(q.p - math::load3<T>(b.pos, i)), rb(q.p - math::load3<T>(b.pos, j));
    const Material<T> pair =
        b.materials.pair(material_of(i, q.feature >> 24), material_of(j, (q.feature >> 16) & 0xffu), defaults.world);
    contacts.set(o, std::uint32_t(i), j, m.n, ra, rb, q.gap, pair.friction, q.feature,
                 bounce(pair.restitution, i, j, m.n, ra, rb, q.gap), pair.spinning, pair.rolling);
  }
  // The material of body i at its part `part` (body_manifolds.hpp's feature
  // bits): a compound's part's own where it names one, else the body's.
  GPUSOLVE_HD std::uint32_t material_of(std::size_t i, std::uint32_t part) const {
    const auto& b = walk.b;
    if constexpr (Walk::compounds)
      if (b.shape[i] == compound)
        if (const std::uint32_t m = b.parts.material[b.first_part[i] + part]) return m;
    return b.material[i];
  }
  // The separation speed restitution asks of a point: e times the approach
  // speed, where the bodies approach faster than the threshold and would
  // close the gap within the step; else 0.
  GPUSOLVE_HD T bounce(T e, std::size_t i, std::uint32_t j, const math::Vector3<T>& n, const math::Vector3<T>& ra,
                       const math::Vector3<T>& rb, T gap) const {
    if (!(e > T(0))) return T(0);
    const auto& b = walk.b;
    const math::Vector3<T> ua = math::load3<T>(b.v, i) + math::load3<T>(b.w, i) % ra;
    const math::Vector3<T> ub = math::load3<T>(b.v, j) + math::load3<T>(b.w, j) % rb;
    const T approach = -math::dot(n, math::Vector3<T>(ua - ub));
    return approach > defaults.bounce_threshold && gap < approach * defaults.dt ? e * approach : T(0);
  }
  // Fills [from, to) with inert contacts of the pair (i, j), apart by more
  // than the margin, along n where it is a unit vector.
  GPUSOLVE_HD void pad(std::uint32_t from, std::uint32_t to, std::size_t i, std::uint32_t j,
                       const math::Vector3<T>& n) const {
    const math::Vector3<T> zero, up(T(0), T(0), T(1));
    const bool unit = math::dot(n, n) > T(0.5);
    const T apart = walk.margin + 2 * (walk.b.radius[i] + walk.b.radius[j]);
    for (std::uint32_t o = from; o < to; ++o)
      contacts.set(o, std::uint32_t(i), j, unit ? n : up, zero, zero, apart, defaults.world.friction, inert_feature);
  }
  // Writes the points of the pair (i, j) at [first, last), exactly filling it.
  GPUSOLVE_HD void pair(std::uint32_t first, std::uint32_t last, std::size_t i, std::uint32_t j) const {
    std::uint32_t o = first;
    math::Vector3<T> normal;
    walk.manifolds(i, j, [&](const Manifold<T>& m) {
      for (int k = 0; k < m.count && o < last; ++k) write(o++, i, j, m, k);
      normal = m.n;
    });
    pad(o, last, i, j, normal);
  }
};

// A ContactWalk's candidate pairs as a walk (CountPartners counts and keeps them).
template <class Walk>
struct CandidateWalk {
  Walk walk;
  template <class F>
  GPUSOLVE_HD void operator()(std::size_t i, F&& visit) const {
    walk.candidates(i, visit);
  }
};

// Writes body i's candidate partners (body i as a, the partners as b, sorted)
// at [offset[i] - count[i], offset[i]) of the candidate list, from the count
// pass's kept list or, for a body with more, from a second walk sorted in
// place. A body whose range passes the list's capacity writes nothing: the
// caller grows the list and repeats.
template <class Walk>
struct WriteCandidates {
  Walk walk;
  const std::uint32_t* offset;  // inclusive scan of the candidate counts
  const std::uint32_t* count;
  const std::uint32_t* kept;
  std::size_t n;
  std::uint32_t *a, *b;
  std::size_t capacity;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const std::uint32_t first = offset[i] - count[i], last = offset[i];
    if (last > capacity) return;
    for (std::uint32_t p = first; p < last; ++p) a[p] = std::uint32_t(i);
    if (count[i] <= kept_candidates) {
      for (std::uint32_t p = 0; p < count[i]; ++p) b[first + p] = kept[p * n + i];
      return;
    }
    std::uint32_t o = first;
    walk.candidates(i, [&](std::uint32_t j) {
      if (o < last) b[o++] = j;
    });
    sort_few(first, o, [&](std::uint32_t p) { return b[p]; }, [&](std::uint32_t p, std::uint32_t j) { b[p] = j; });
    for (; o < last; ++o) b[o] = std::uint32_t(i);  // fewer than counted (the passes compile apart): no pair
  }
};

// The number of contact points of candidate pair k (0 past the candidates
// listed: the pass runs over the list's whole capacity, its count stays on the
// device). A pair whose points form one manifold (two primitives; a compound
// whose part pairs' manifolds merged into one) keeps it in manifold[k] for the
// write pass (computed once, and the two passes cannot disagree); a pair with
// several is marked count -1 and written from its manifolds computed again.
// Where the walk compiles compounds in, their pairs take a pass of their own
// (`Compounds`), launched after this one and only while the scene holds one:
// this pass leaves them no points, and holds no compound code, whose registers
// (155 against 114 for every other pair, sm_90) would thin every pair's kernel.
template <class Walk, class T, bool Compounds = false>
struct CountPairPoints {
  Walk walk;
  const std::uint32_t *a, *b;
  const std::uint32_t* candidates;  // how many are listed
  std::size_t capacity;
  std::uint32_t* points;
  Manifold<T>* manifold;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    const bool listed = k < *candidates && *candidates <= capacity && a[k] != b[k];
    std::uint32_t p = 0;
    Manifold<T> m;
    if constexpr (Compounds) {
      if (!listed || !walk.holds_compound(a[k], b[k])) return;
      p = walk.points(a[k], b[k], m);
    } else if (listed && walk.primitive_manifold(a[k], b[k], m)) {
      p = std::uint32_t(m.count);
    }
    points[k] = p;
    if (p > 0) manifold[k] = m;
  }
};

// Writes candidate pair k's points at [offset[k] - points[k], offset[k]),
// unless that passes the contacts' capacity (their view's size): the caller
// grows and repeats. Pair 0's thread also writes the summary the host reads.
// A pair of several manifolds (count -1, a compound's) is written from its
// manifolds computed again, by a pass of its own (`Compounds`) as in CountPairPoints.
template <class Writer, class Summary, class T, bool Compounds = false>
struct WritePairContacts {
  Writer writer;
  const std::uint32_t *a, *b;
  const std::uint32_t* offset;  // inclusive scan of the points
  const std::uint32_t* points;
  const Manifold<T>* manifold;
  Summary summarize;
  GPUSOLVE_HD void operator()(std::size_t k) const {
    if (!Compounds && k == 0) summarize(0);
    if (points[k] == 0 || offset[k] > writer.contacts.size()) return;
    const std::uint32_t first = offset[k] - points[k];
    if constexpr (Compounds) {
      if (manifold[k].count < 0) writer.pair(first, offset[k], a[k], b[k]);
    } else {
      const Manifold<T> m = manifold[k];
      for (int q = 0; q < m.count; ++q) writer.write(first + std::uint32_t(q), a[k], b[k], m, q);
    }
  }
};

}  // namespace gpusolve::rbd::detail
