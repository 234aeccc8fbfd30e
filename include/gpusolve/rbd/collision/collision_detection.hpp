// Collision detection where the bodies live: the broad phase's grid walked for
// pairs of bounding spheres, every moving body against the few obstacles
// (planes, large fixed bodies), the shape-pair table for their manifolds, and
// the contacts written by a count pass, a scan and a write pass, all queued on
// one stream; the host reads the counts once per step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include <limits>
#include <type_traits>

#include <cuda/atomic>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"
#include "gpusolve/rbd/collision/box_slabs.hpp"
#include "gpusolve/rbd/collision/broad_phase.hpp"
#include "gpusolve/rbd/contacts/contacts.hpp"
#include "gpusolve/rbd/collision/body_manifolds.hpp"
#include "gpusolve/rbd/collision/kept_partners.hpp"
#include "gpusolve/rbd/collision/pair_passes.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/execution/graph_replay.hpp"
#include "gpusolve/container/ensure_size.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/rbd/settings/contact_settings.hpp"

namespace gpusolve::rbd {
namespace detail {

// Body i is an obstacle: a plane, or a fixed body too large for the grid's
// cells, not removed. Obstacles are met by every moving body on the grid.
template <class View, class T>
GPUSOLVE_HD bool obstacle(const View& b, std::size_t i, const GridGeometry<T>& g, T margin) {
  if (b.status[i] != fixed) return false;  // a moving body is always on the grid
  return b.shape[i] == plane || (grid_candidate(b, i) && !g.holds(b, i, margin));
}

// Appends body i to the obstacles. The list's order differs from run to run
// (an atomic counter, cleared before); contacts come out sorted by b whatever
// the order a walk meets them in.
template <class View, class T>
struct ListObstacles {
  View b;
  const T* cell;
  T margin;
  std::uint32_t *obstacles, *count;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (!obstacle(b, i, GridGeometry<T>(cell, 0u), margin)) return;
    const std::uint32_t k = cuda::atomic_ref<std::uint32_t, cuda::thread_scope_device>(*count).fetch_add(
        1u, cuda::std::memory_order_relaxed);
    obstacles[k] = std::uint32_t(i);
  }
};

// The contact pairs of body i as body a: its grid neighbours j > i (a fixed
// body or a shadow only with active ones) and, for an active body, the obstacles.
// candidates() lists those whose bounds meet; manifolds(i, j, ...) are a
// pair's, over the kinds in M (body_manifolds.hpp); where M holds spheres and
// planes only, no other pair is compiled in, and the walk itself finds the
// pairs that touch (operator()).
template <class View, class T, ShapeMask M>
struct ContactWalk {
  View b;
  T margin;
  NeighbourWalk<View, T> grid;
  const std::uint32_t* obstacles;       // body indices (ListObstacles)
  const std::uint32_t* obstacle_count;  // their number

  static constexpr bool spheres_only = (M & ~spheres_and_planes) == 0;
  static constexpr bool compounds = (M & shape_bit(compound)) != 0;

  // The one manifold of sphere i against sphere or plane j (spheres_only).
  GPUSOLVE_HD Manifold<T> sphere_manifold(std::size_t i, std::uint32_t j) const {
    const math::Vector3<T> pa = math::load3<T>(b.pos, i);
    if (b.shape[j] == plane)
      return within_margin(sphere_plane(pa, b.radius[i], math::Vector3<T>(b.shape_param(j, 0), b.shape_param(j, 1),
                                                                         b.shape_param(j, 2)),
                                        b.shape_param(j, 3)),
                           margin);
    return within_margin(sphere_sphere(pa, b.radius[i], math::load3<T>(b.pos, j), b.radius[j]), margin);
  }

  // Calls f(m) for each manifold with points of the pair (i, j).
  template <class F>
  GPUSOLVE_HD void manifolds(std::size_t i, std::uint32_t j, F&& f) const {
    if constexpr (spheres_only) {
      const Manifold<T> m = sphere_manifold(i, j);
      if (m.count > 0) f(m);
    } else {
      for_each_manifold<M, T>(b, i, j, margin, f);
    }
  }
  // The one manifold of two primitives (true; no points where their gap
  // passes the margin), or false where either body is a compound.
  GPUSOLVE_HD bool primitive_manifold(std::size_t i, std::uint32_t j, Manifold<T>& m) const {
    if (holds_compound(i, j)) return false;
    m = collide<M & primitives, T>(b.shape[i], placed_shape<T>(b, i), b.shape[j], placed_shape<T>(b, j), margin);
    return true;
  }
  // Whether body i or body j is a compound.
  GPUSOLVE_HD bool holds_compound(std::size_t i, std::uint32_t j) const {
    return compounds && (b.shape[i] == compound || b.shape[j] == compound);
  }
  // The number of contact points of the pair (i, j).
  GPUSOLVE_HD std::uint32_t points(std::size_t i, std::uint32_t j) const {
    std::uint32_t count = 0;
    manifolds(i, j, [&](const Manifold<T>& m) { count += std::uint32_t(m.count); });
    return count;
  }
  // points(i, j), keeping the pair's manifold in `one` where its points form
  // one (a compound resting on one face, merged), else one.count = -1.
  GPUSOLVE_HD std::uint32_t points(std::size_t i, std::uint32_t j, Manifold<T>& one) const {
    std::uint32_t count = 0;
    int found = 0;
    one.count = 0;
    manifolds(i, j, [&](const Manifold<T>& m) {
      count += std::uint32_t(m.count);
      if (found++ == 0) one = m;
    });
    if (found > 1) one.count = -1;
    return count;
  }

  // Whether moving body i's bounding sphere comes within the margin of
  // obstacle j: of a plane's surface (or behind it), of a large body's sphere.
  GPUSOLVE_HD bool near_obstacle(std::size_t i, std::uint32_t j) const {
    const math::Vector3<T> x = math::load3<T>(b.pos, i);
    if (b.shape[j] == plane)
      return math::dot(math::Vector3<T>(b.shape_param(j, 0), b.shape_param(j, 1), b.shape_param(j, 2)), x) -
                 b.shape_param(j, 3) <
             b.radius[i] + margin;
    const math::Vector3<T> d(x - math::load3<T>(b.pos, j));
    const T reach = b.radius[i] + b.radius[j] + margin;
    return math::dot(d, d) < reach * reach;
  }

  // Calls visit(j) for each candidate partner j of body i: the grid
  // neighbours j > i whose bounding spheres come within the margin (a fixed
  // body or a shadow only with active ones; where i is a box, only those that
  // reach into its slabs: BoxSlabs) and, for an active body, the
  // obstacles near it; the pairs whose manifolds the pair passes (pair_passes.hpp) compute.
  template <class F>
  GPUSOLVE_HD void candidates(std::size_t i, F&& visit) const {
    const GridGeometry<T> g(grid.cell, grid.mask);
    if (!g.holds(b, i, margin)) return;
    const bool active_a = b.status[i] == active;
    const BoxSlabs<T> slabs(b, i);
    grid(i, [&](std::uint32_t j, const GridSphere<T>& o) {
      if (!active_a && b.status[j] != active) return;
      if (slabs.apart(o, margin) && slabs_decide(ShapeKind(b.shape[j]))) return;
      visit(j);
    });
    if (!active_a) return;
    for (std::uint32_t k = 0; k < *obstacle_count; ++k)
      if (near_obstacle(i, obstacles[k])) visit(obstacles[k]);
  }

  // Calls visit(j) for each partner j of sphere i that it meets within the
  // margin, in the order of candidates(): the one-pass walk of a detection
  // whose bodies are spheres and planes (spheres_only); every other detection
  // goes through the pair passes. Between two spheres the gap comes from the
  // grid's packed copies (the same floats as the manifold's).
  template <class F>
  GPUSOLVE_HD void operator()(std::size_t i, F&& visit) const {
    static_assert(spheres_only, "ContactWalk: bodies other than spheres go through the pair passes");
    const GridGeometry<T> g(grid.cell, grid.mask);
    if (!g.holds(b, i, margin)) return;
    const bool active_a = b.status[i] == active;
    const GridSphere<T> me = grid_sphere<View, T>(b, i);
    const math::Vector3<T> pa(me.x[0], me.x[1], me.x[2]);
    grid(i, [&](std::uint32_t j, const GridSphere<T>& o) {
      if (!active_a && b.status[j] != active) return;
      if (sphere_sphere(pa, me.r, math::Vector3<T>(o.x[0], o.x[1], o.x[2]), o.r).points[0].gap < margin) visit(j);
    });
    if (!active_a) return;
    for (std::uint32_t k = 0; k < *obstacle_count; ++k)
      if (points(i, obstacles[k]) > 0) visit(obstacles[k]);
  }
};

// What the host reads once per detection: the counts it must size for, and
// the cell size (not finite: a radius or the margin is not finite).
template <class T>
struct DetectionSummary {
  std::uint32_t contacts;
  T cell;
  std::uint64_t non_finite;  // NonFiniteKey's minimum: the first body with a NaN or inf in its state
  std::uint32_t candidates = 0;  // candidate pairs listed (the pair passes; 0 where spheres walk alone)
};

// Throws what makes a detection's contacts unusable: NonFiniteStateError
// naming the first body whose state is not finite, InvalidArgumentError for a
// radius or margin that is not finite.
template <class T>
void require_usable(const DetectionSummary<T>& s) {
  if (s.non_finite != ~std::uint64_t(0)) throw non_finite_state(s.non_finite);
  if (!(s.cell <= std::numeric_limits<T>::max()))
    throw InvalidArgumentError("gpusolve: CollisionDetection: a bounding radius or the margin is not finite");
}

// One reduction over the bodies for the grid's cell size (BodyReach's
// maximum) and the first body whose state is not finite (NonFiniteKey's
// minimum), where two would each evaluate and reduce.
template <class T>
struct BodyScan {
  T cell;
  std::uint64_t non_finite;
};
template <class View, class T>
struct ScanBody {
  BodyReach<View, T> reach;
  NonFiniteKey<View> key;
  GPUSOLVE_HD BodyScan<T> operator()(std::size_t i) const { return {reach(i), key(i)}; }
};
struct BodyScanOp {
  template <class T>
  GPUSOLVE_HD BodyScan<T> operator()(const BodyScan<T>& x, const BodyScan<T>& y) const {
    return {MaxOp{}(x.cell, y.cell), MinOp{}(x.non_finite, y.non_finite)};
  }
};

// Writes the summary, and sets *hold (where there is one) when the step must
// not go on: more contacts or candidate pairs than their capacities, or what
// require_usable throws for.
template <class T>
struct Summarize {
  const std::uint32_t* contacts;
  const BodyScan<T>* scan;
  DetectionSummary<T>* out;
  std::uint32_t* hold;
  std::size_t capacity;
  const std::uint32_t* candidates = nullptr;  // the pair passes' count, or none
  std::size_t candidate_capacity = 0;
  GPUSOLVE_HD void operator()(std::size_t) const {
    const DetectionSummary<T> s{*contacts, scan->cell, scan->non_finite, candidates ? *candidates : 0u};
    *out = s;
    if (hold != nullptr && (s.contacts > capacity || s.candidates > candidate_capacity ||
                            s.non_finite != ~std::uint64_t(0) || !(s.cell <= std::numeric_limits<T>::max())))
      *hold = 1;
  }
};

// Writes sphere i's contacts at [offset[i] - count[i], offset[i]) in
// increasing order of body b (spheres_only: one point per pair), unless that
// passes the contacts' capacity (their view's size): the caller grows and
// repeats. The partners come from the count pass's kept list or, for a body
// with more, from a second walk, listed in the b column and sorted in place.
// The two passes compile the same arithmetic separately, so the range still
// fills exactly: a pair no longer found gets an inert contact. Body 0's
// thread also writes the summary the host reads.
template <class Walk, class ContactView, class T>
struct WriteContacts {
  PointWriter<Walk, ContactView, T> writer;
  const std::uint32_t* offset;  // inclusive scan of the counts
  const std::uint32_t* count;
  const std::uint32_t* kept;
  std::size_t n;
  Summarize<T> summarize;

  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (i == 0) summarize(0);
    if (offset[i] > writer.contacts.size()) return;
    const std::uint32_t first = offset[i] - count[i], last = offset[i];
    if (count[i] <= kept_contacts) {
      for (std::uint32_t o = first; o < last; ++o) write_one(o, i, kept[(o - first) * n + i]);
      return;
    }
    const auto& c = writer.contacts;
    std::uint32_t found = first;
    writer.walk(i, [&](std::uint32_t j) {
      if (found < last) c.b[found++] = j;
    });
    sort_few(first, found, [&](std::uint32_t p) { return std::uint32_t(c.b[p]); },
             [&](std::uint32_t p, std::uint32_t j) { c.b[p] = j; });
    for (std::uint32_t o = first; o < found; ++o) write_one(o, i, c.b[o]);
    if (found < last) writer.pad(found, last, i, kept[i], math::Vector3<T>());
  }

  // A sphere pair's one point (or an inert contact where it is no longer found).
  GPUSOLVE_HD void write_one(std::uint32_t o, std::size_t i, std::uint32_t j) const {
    const Manifold<T> m = writer.walk.sphere_manifold(i, j);
    if (m.count > 0)
      writer.write(o, i, j, m, 0);
    else
      writer.pad(o, o + 1, i, j, m.n);
  }
};

// What the launches of one detection depend on besides the sizes of its
// scratch stores, which stay put while the body count does: the bodies' and
// contacts' views (their pointers and sizes), the margin and the friction
// coefficient. A captured graph of the detection is launched again while
// these are the same (GraphReplay).
template <class View, class ContactView, class T>
struct DetectionKey {
  View bodies;
  ContactView contacts;
  T margin;
  ContactDefaults<T> defaults;
  std::uint32_t* hold;
  ShapeMask shapes;

  // GraphReplay compares keys byte by byte, padding included: zeroed here, or
  // what the stack held there would make the same detection capture again.
  // The views have no padding of their own to carry such bytes in.
  static_assert(std::has_unique_object_representations_v<View> &&
                std::has_unique_object_representations_v<ContactView>);
  DetectionKey(const View& b, const ContactView& c, T m, const ContactDefaults<T>& d, std::uint32_t* h,
               ShapeMask s) {
    std::memset(static_cast<void*>(this), 0, sizeof(*this));
    bodies = b, contacts = c, margin = m, defaults = d, hold = h, shapes = s;
  }
};

}  // namespace detail

// Rebuilds the contacts of the bodies every step, on their backend. A contact
// is made wherever two surfaces are closer than `margin` (not only where they
// touch), so the solver can stop bodies before they meet. A pair of shapes
// gives up to max_manifold_points contacts; contacts come sorted by (a, b)
// on every backend, a pair's points in their manifold's order. Shapes: the
// kinds compiled in (a sphere-only program need not compile box pairs);
// where the bodies hold spheres and planes only (Bodies::shapes), no other
// shape pair runs. Scratch storage is kept between steps.
template <class Device, class T = float, ShapeMask Shapes = all_shapes>
class CollisionDetection {
 public:
  using View = typename Bodies<Device, T>::View;
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;

  // Fills `contacts` (their friction and bounce from the bodies' materials,
  // material 0 being defaults.world; a plain friction coefficient converts) and
  // returns their number. The work is queued on `stream`; the host waits once,
  // at the end, for the counts (and again only when a list had to grow).
  // Throws NonFiniteStateError naming the first body (not removed) whose
  // position, orientation or velocity is NaN or infinite; bodies are never written.
  template <class Model>
  std::size_t detect(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, T margin,
                     const ContactDefaults<T>& defaults = {},
                     stream_t stream = stream_t{}) {
    empty_ = !begin(bodies, contacts, margin);
    if (empty_) return 0;
    for (;;) {
      queue_detection(bodies, contacts, margin, defaults, nullptr, stream);
      const detail::DetectionSummary<T> s = summary(stream);
      detail::require_usable(s);
      if (grow_for(s)) continue;  // the candidate list was short: the contacts' count is not yet known
      if (s.contacts <= contacts.capacity()) {
        contacts.resize(s.contacts);
        return s.contacts;
      }
      contacts.resize(s.contacts);
    }
  }

  // detect() without a host wait, for a step that goes on on the device
  // (World::advance_unattended): the contacts keep their capacity as their
  // size, and their count stays in device memory (Contacts::count_on_device).
  // Where the step must not go on, the detection sets *hold to 1 (a word of
  // the backend's memory; nothing clears it): more contacts than the
  // capacity (those past it are not written), or what detect() throws for.
  // summary() says which, once the stream has passed the detection.
  template <class Model>
  void detect_queued(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, T margin,
                     const ContactDefaults<T>& defaults,
                     std::uint32_t* hold, stream_t stream = stream_t{}) {
    const std::size_t expected = contacts.expected_size();
    empty_ = !begin(bodies, contacts, margin);
    if (empty_) return;
    queue_detection(bodies, contacts, margin, defaults, hold, stream);
    contacts.count_on_device(&summary_.data()->contacts, expected);
  }

  // Grows the candidate list where a detection's summary says it was short
  // (a held unattended step must grow it before it is queued again); true
  // where it grew.
  bool grow_for(const detail::DetectionSummary<T>& s) {
    if (s.candidates <= candidate_a_.size_x()) return false;
    for (D1<std::uint32_t>* v : {&candidate_a_, &candidate_b_, &pair_points_, &point_offset_})
      gpusolve::detail::ensure_size(*v, s.candidates);
    manifolds_.resize(candidate_a_.size_x());  // one per candidate: 96 bytes each, no slack on top of the list's
    sized_for_ = 0;  // a kept graph points to the old stores
    return true;
  }

  // The summary of the last detection; waits for it.
  detail::DetectionSummary<T> summary(stream_t stream = stream_t{}) const {
    if (empty_) return {0u, T(0), ~std::uint64_t(0)};  // no bodies: nothing was queued
    return detail::read_back<Device>(summary_.data(), 0, stream);
  }

  // GPU: queue the detection's kernels as one CUDA graph (execution/graph_replay.hpp),
  // captured once and launched again while the bodies, the contacts' storage
  // and the parameters stay (DetectionKey); off by default, the World follows
  // SolverSettings::detection_graph.
  void set_graphs(bool on) { graphs_ = on; }
  // The room per body the contacts start with (ContactSettings::contacts_per_body).
  void set_contacts_per_body(std::size_t k) { contacts_per_body_ = k; }

 private:
  // Validates the margin and sizes the scratch; false where there are no bodies (and no contacts).
  template <class Model>
  bool begin(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, T margin) {
    if (!(margin >= 0)) throw InvalidArgumentError("gpusolve: CollisionDetection: margin must be >= 0");
    contacts.count_on_device(nullptr);
    const std::size_t n = bodies.view().size();
    if (n == 0) {
      contacts.resize(0);
      return false;
    }
    gpusolve::detail::ensure_size(obstacles_, n);
    gpusolve::detail::ensure_size(obstacle_count_, 1);
    gpusolve::detail::ensure_size(count_, n);
    gpusolve::detail::ensure_size(offset_, n);
    const bool pair_passes = takes_pair_passes(bodies);
    gpusolve::detail::ensure_size(kept_, (pair_passes ? detail::kept_candidates : detail::kept_contacts) * n);
    gpusolve::detail::ensure_size(summary_, 1);
    gpusolve::detail::ensure_size(scan_, 1);
    if (contacts.capacity() < contacts_per_body_ * n) contacts.resize(contacts_per_body_ * n);
    if (pair_passes && candidate_a_.size_x() < 4 * n) {
      for (D1<std::uint32_t>* v : {&candidate_a_, &candidate_b_, &pair_points_, &point_offset_})
        gpusolve::detail::ensure_size(*v, 4 * n);
      manifolds_.resize(candidate_a_.size_x());
      sized_for_ = 0;
    }
    return true;
  }

  // Queues one detection into the contacts' whole capacity (their size).
  template <class Model>
  void queue_detection(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, T margin,
                       const ContactDefaults<T>& defaults,
                       std::uint32_t* hold, stream_t stream) {
    const View b = bodies.view();
    const std::size_t n = b.size();
    contacts.resize(contacts.capacity());  // written up to the capacity; detect() trims
    const auto cv = contacts.view();
    auto queue = [&](stream_t q) { queue_contacts(bodies, cv, margin, defaults, hold, q); };
    if (graphs_ && sized_for_ == n) {  // every scratch store sized: nothing allocates in the capture
      using Key = detail::DetectionKey<View, std::remove_const_t<decltype(cv)>, T>;
      const Key key{b, cv, margin, defaults, hold, bodies.shapes};
      graph_.run(key, queue, stream);
    } else {  // scratch may have moved: no kept graph may point to it
      graph_.forget();
      queue(stream);
      sized_for_ = n;
    }
  }

  template <class CView>
  void queue_contacts(Bodies<Device, T>& bodies, const CView& c, T margin, const ContactDefaults<T>& defaults,
                      std::uint32_t* hold,
                      stream_t stream) {
    if ((bodies.shapes & ~Shapes) != 0)
      throw InvalidArgumentError("gpusolve: CollisionDetection: the bodies hold shape kinds that were not compiled in "
                                 "(its Shapes)");
    if constexpr ((Shapes & ~spheres_and_planes) != 0)
      if (takes_pair_passes(bodies)) return queue_contacts<Shapes>(bodies, c, margin, defaults, hold, stream);
    queue_contacts<spheres_and_planes>(bodies, c, margin, defaults, hold, stream);
  }

  // Whether a detection of these bodies runs the pair passes (queue_pair_passes)
  // rather than the spheres' walk: the one place that decides, so that the
  // scratch begin() sizes (the kept partners) is the path's.
  static bool takes_pair_passes(const Bodies<Device, T>& bodies) {
    return (Shapes & ~spheres_and_planes) != 0 && (bodies.shapes & ~spheres_and_planes) != 0;
  }

  template <ShapeMask M, class CView>
  void queue_contacts(Bodies<Device, T>& bodies, const CView& c, T margin, const ContactDefaults<T>& defaults,
                      std::uint32_t* hold,
                      stream_t stream) {
    const View b = bodies.view();
    const std::size_t n = b.size();
    const Device dev{};
    algorithms_.reduce_into(n, detail::ScanBody<View, T>{{b, margin}, {b}},
                            detail::BodyScan<T>{T(0), ~std::uint64_t(0)}, detail::BodyScanOp{}, scan_.data(), stream);
    const auto grid = grid_.queue_grid(bodies, margin, stream, &scan_.data()->cell);
    obstacle_count_.fill(0u, stream);
    launch(dev, n,
           detail::ListObstacles<View, T>{b, grid.cell, margin, obstacles_.data(), obstacle_count_.data()}, stream);
    using Walk = detail::ContactWalk<View, T, M>;
    const Walk walk{b, margin, grid, obstacles_.data(), obstacle_count_.data()};
    const detail::PointWriter<Walk, CView, T> writer{walk, c, defaults};
    if constexpr (Walk::spheres_only) {
      launch(dev, n, detail::CountPartners<Walk>{walk, count_.data(), kept_.data(), n}, stream);
      algorithms_.inclusive_sum(count_.data(), offset_.data(), n, stream);
      launch(dev, n,
             detail::WriteContacts<Walk, CView, T>{writer, offset_.data(), count_.data(), kept_.data(), n,
                                                   {offset_.data() + (n - 1), scan_.data(), summary_.data(), hold,
                                                    c.bound()}},
             stream);
    } else {
      queue_pair_passes(walk, writer, n, hold, c.bound(), (bodies.shapes & shape_bit(compound)) != 0, stream);
    }
  }

  // Candidates per body (the count pass over CandidateWalk, then a scan),
  // listed per pair, then each pair's points counted, scanned and written by
  // a thread of its own. The passes run over the candidate list's capacity,
  // so no count comes back to the host between them. Compound pairs take
  // passes of their own, queued only while the scene holds a compound.
  template <class Walk, class Writer>
  void queue_pair_passes(const Walk& walk, const Writer& writer, std::size_t n, std::uint32_t* hold,
                         std::size_t contact_capacity, bool compounds, stream_t stream) {
    const Device dev{};
    const std::size_t capacity = candidate_a_.size_x();
    const std::uint32_t* candidates = offset_.data() + (n - 1);
    using CountCandidates = detail::CountPartners<detail::CandidateWalk<Walk>, detail::kept_candidates>;
    launch(dev, n, CountCandidates{{walk}, count_.data(), kept_.data(), n}, stream);
    algorithms_.inclusive_sum(count_.data(), offset_.data(), n, stream);
    launch(dev, n,
           detail::WriteCandidates<Walk>{walk, offset_.data(), count_.data(), kept_.data(), n, candidate_a_.data(),
                                         candidate_b_.data(), capacity},
           stream);
    const auto count = [&](auto pass) {
      launch(dev, capacity,
             detail::CountPairPoints<Walk, T, decltype(pass)::value>{walk, candidate_a_.data(), candidate_b_.data(),
                                                                     candidates, capacity, pair_points_.data(),
                                                                     manifolds_.data()},
             stream);
    };
    count(std::false_type{});
    if constexpr (Walk::compounds)
      if (compounds) count(std::true_type{});
    algorithms_.inclusive_sum(pair_points_.data(), point_offset_.data(), capacity, stream);
    const auto write = [&](auto pass) {
      launch(dev, capacity,
             detail::WritePairContacts<Writer, detail::Summarize<T>, T, decltype(pass)::value>{
                 writer, candidate_a_.data(), candidate_b_.data(), point_offset_.data(), pair_points_.data(),
                 manifolds_.data(),
                 {point_offset_.data() + (capacity - 1), scan_.data(), summary_.data(), hold, contact_capacity,
                  candidates, capacity}},
             stream);
    };
    write(std::false_type{});
    if constexpr (Walk::compounds)
      if (compounds) write(std::true_type{});
  }

  UniformGrid<Device, T> grid_;
  D1<std::uint32_t> obstacles_, obstacle_count_, count_, offset_, kept_;
  D1<std::uint32_t> candidate_a_, candidate_b_, pair_points_, point_offset_;  // the pair passes' list
  D1<Manifold<T>> manifolds_;  // a primitive pair's manifold, from its count pass to its write pass
  D1<detail::BodyScan<T>> scan_;
  D1<detail::DetectionSummary<T>> summary_;
  detail::DeviceAlgorithms<Device> algorithms_;
  detail::GraphReplay<Device> graph_;
  bool graphs_ = false, empty_ = false;
  std::size_t contacts_per_body_ = ContactSettings<T>{}.contacts_per_body;
  std::size_t sized_for_ = 0;  // the body count the scratch stores were last sized for
};

}  // namespace gpusolve::rbd
