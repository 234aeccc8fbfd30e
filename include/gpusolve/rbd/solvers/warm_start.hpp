// Warm starting: each contact that persists from the previous step starts the
// solve from (a fraction of) the impulse it ended that step with.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <thrust/binary_search.h>
#include <thrust/copy.h>
#include <thrust/execution_policy.h>
#include <thrust/gather.h>
#include <thrust/sequence.h>
#include <thrust/sort.h>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/collision/broad_phase.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/solvers/friction_anchors.hpp"
#include "gpusolve/rbd/contacts/extent.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/container/ensure_size.hpp"

namespace gpusolve::rbd {

namespace detail {

// The impulse a contact keeps for the next step, Model::rows values. With
// friction the world vector Q x (linear, then angular where the model has
// angular rows): the tangents are rebuilt from each step's
// normal (Contacts::View::set_tangents) and may turn, even swap axes, from one
// step to the next, so the impulse is re-expressed in the new frame rather than
// copied row by row. Frictionless: the normal impulse itself. With friction
// anchors, after it the slip a sticking contact keeps (friction_anchors.hpp).
// Index 0 also records the contacts' count, which the next step's carry
// reads where it runs (the count may be known only to the device).
template <class Model, class CV, class T>
struct RememberImpulse {
  CV c;
  std::uint64_t* keys;
  std::uint32_t* features;
  VectorD2View<T> p;  // contacts x Model::rows
  std::uint32_t* count;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const std::size_t n = c.size();
    if (i == 0) *count = std::uint32_t(n);
    if (i >= n) return;
    keys[i] = pair_key(c.a[i], c.b[i]);
    features[i] = c.feature[i];
    if constexpr (Model::linear_rows == 3) {
      T x[Model::rows];
      for (std::size_t r = 0; r < Model::rows; ++r) x[r] = c.x(i, r);
      const Frame<T, Model, CV> f(c, i);
      const math::Vector3<T> w = f.linear(x);
      for (std::size_t k = 0; k < 3; ++k) p(i, k) = w[k];
      if constexpr (Model::rows > 3) {
        const math::Vector3<T> m = f.angular(x);
        for (std::size_t k = 0; k < 3; ++k) p(i, 3 + k) = m[k];
      }
      if (c.anchored) remember_anchor<Model>(c, i, x, p, Model::rows);
    } else {
      p(i, 0) = c.x(i, 0);
    }
  }
};

// The first position p in the sorted keys[0, count) with keys[p] >= key, found
// by galloping from `guess`, then a binary search: about 2 log2 |p - guess|
// dependent loads instead of log2 count.
GPUSOLVE_HD inline std::size_t lower_bound_near(const std::uint64_t* keys, std::size_t count, std::uint64_t key,
                                                std::size_t guess) {
  if (count == 0) return 0;
  const std::size_t g = guess < count ? guess : count - 1;
  std::size_t lo, hi, b = 1;
  if (keys[g] < key) {  // p in (g, count]
    while (g + b < count && keys[g + b] < key) b *= 2;
    lo = g + b / 2 + 1;
    hi = g + b < count ? g + b : count;  // keys[hi] >= key, or hi = count
  } else {  // p in [0, g]
    while (b <= g && keys[g - b] >= key) b *= 2;
    lo = b <= g ? g - b + 1 : 0;
    hi = g - b / 2;  // keys[hi] >= key
  }
  return std::size_t(thrust::lower_bound(thrust::seq, keys + lo, keys + hi, key) - keys);
}

// x of contact i: factor times the remembered impulse of the same point (body
// pair and feature id) in the contact's new frame, projected onto the
// admissible set (the normal may have turned); zero for a point that was not
// in contact; where the contacts carry friction anchors, also its slip
// (friction_anchors.hpp). Both steps' contacts are sorted by (a, b) and most
// pairs persist, so the pair is searched for from the contact's index scaled
// to the previous list's length, then its few points for the feature.
template <class Model, class BV, class CV, class T>
struct CarryImpulse {
  BV b;  // the bodies' velocities: friction anchors
  CV c;
  const std::uint64_t* keys;  // previous step's pair keys, sorted
  const std::uint32_t* features;
  Extent previous;            // their number
  VectorD2View<T> p;
  T factor;
  T dt;  // the step's length: friction anchors
  GPUSOLVE_HD void operator()(std::size_t i) const {
    constexpr std::size_t R = Model::rows;
    if (i >= c.size()) return;
    const std::size_t count = previous.size();
    const std::uint64_t key = pair_key(c.a[i], c.b[i]);
    std::size_t j = lower_bound_near(keys, count, key, std::size_t(std::uint64_t(i) * count / c.size()));
    const std::uint32_t feature = c.feature[i];
    while (j < count && keys[j] == key && features[j] != feature) ++j;
    T x[R] = {};
    const bool found = j < count && keys[j] == key;
    if constexpr (Model::linear_rows == 3)
      if (c.anchored) {
        T kept[anchor_values];
        const bool anchored = found && p.size_y() == R + anchor_values;  // the last step kept anchors
        for (std::size_t k = 0; k < anchor_values && anchored; ++k) kept[k] = p(j, R + k);
        carry_anchor(b, c, i, anchored ? kept : nullptr, dt);
      }
    if (found) {
      if constexpr (Model::linear_rows == 3) {
        const Frame<T, Model, CV> f(c, i);
        const math::Vector3<T> w(p(j, 0), p(j, 1), p(j, 2));
        math::Vector3<T> m;
        if constexpr (R > 3) m = math::Vector3<T>(p(j, 3), p(j, 4), p(j, 5));
        f.rows(w, m, x);
        for (std::size_t r = 0; r < R; ++r) x[r] *= factor;
      } else {
        x[0] = factor * p(j, 0);
      }
      Model::project(x, limits_of<Model, T>(c, i));
    }
    for (std::size_t r = 0; r < R; ++r) c.x(i, r) = x[r];
  }
};

// A remembered pair after the bodies moved to new slots (slot s to moved[s];
// SpatialOrder): its key in the new numbering, with the roles detection gives
// the pair there: a moving body before a fixed one, else the lower slot first
// (ContactWalk::candidates). Where the roles swap, the kept values, world
// vectors acting on body a (impulse, angular impulse, anchor slip), change
// sign; a frictionless normal impulse is the same either way. The points keep
// their feature ids, which for a box pair that swapped name other features:
// those start cold for one step.
template <class Model, class BV, class T>
struct RenumberPair {
  BV b;  // in the new order
  std::uint64_t* keys;
  VectorD2View<T> p;
  const std::uint32_t* moved;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    std::uint32_t a = moved[pair_a(keys[i])], c = moved[pair_b(keys[i])];
    const bool fixed_a = !b.moving(a), fixed_c = !b.moving(c);
    const bool swap = fixed_a != fixed_c ? fixed_a : a > c;
    if (swap) {
      const std::uint32_t t = a;
      a = c, c = t;
      if constexpr (Model::linear_rows == 3)
        for (std::size_t r = 0; r < p.size_y(); ++r) p(i, r) = -p(i, r);
    }
    keys[i] = pair_key(a, c);
  }
};

}  // namespace detail

// Remembered contacts on the host (WarmStart::host_copy): per contact its
// pair key (pair_key(a, b)), feature id and `width` values (WarmStart's rows).
template <class T>
struct RememberedContacts {
  std::vector<std::uint64_t> keys;
  std::vector<std::uint32_t> features;
  std::vector<T> values;
  std::size_t width = 0;
};

// The previous step's pair keys and impulses, kept on the contacts' backend (no
// host round trip). carry() after collision detection fills contacts.x; the
// solver must then start from it (JacobiSolver::solve with from_x). remember()
// after the solve. Body indices are the pair's identity: a body slot replaced
// through BodyManager::bodyAdded may inherit its predecessor's impulse for one
// step, which the solve then corrects like any other starting error.
template <class Device, class T, class Model>
class WarmStart {
 public:
  // With friction anchors (c.anchored) the bodies' velocities must still be
  // those the last step ended with, and dt its length.
  template <class BV, class CV>
  void carry(const BV& b, const CV& c, T factor, T dt, stream_t stream = stream_t{}) {
    if (c.bound() != 0) launch(Device{}, c.bound(), carrier(b, c, factor, dt), stream);
  }
  // carry() as a functor over the contacts' bound, for a caller that launches it.
  template <class BV, class CV>
  detail::CarryImpulse<Model, BV, CV, T> carrier(const BV& b, const CV& c, T factor, T dt) {
    return {b, c, keys_.data(), features_.data(), {count_, count_ != 0 ? live_.data() : nullptr}, p_.view(), factor, dt};
  }
  template <class CV>
  void remember(const CV& c, stream_t stream = stream_t{}) {
    const auto f = rememberer(c, true, stream);
    if (count_ != 0) launch(Device{}, count_, f, stream);
  }
  // remember() as a functor over the remembered() contacts, for a caller that
  // runs it in a pass of its own; storage is sized here. Without `on`, forget().
  // Growing keeps what was remembered: a step queued unattended and held
  // (World::advance_unattended) changes nothing, and when it is queued again
  // it carries the impulses of the step before it.
  template <class CV>
  detail::RememberImpulse<Model, CV, T> rememberer(const CV& c, bool on = true, stream_t stream = stream_t{}) {
    count_ = on ? c.bound() : 0;
    if (count_ != 0) {
      gpusolve::detail::ensure_size_keeping(keys_, count_, 1, stream);
      gpusolve::detail::ensure_size_keeping(features_, count_, 1, stream);
      const std::size_t values = Model::rows + (c.anchored ? detail::anchor_values : 0);
      gpusolve::detail::ensure_size_keeping(p_, count_, values, stream);
      gpusolve::detail::ensure_size(live_, 1);
    }
    return {c, keys_.data(), features_.data(), p_.view(), live_.data()};
  }
  // No impulses to carry (warm starting off): the next carry() starts all from zero.
  void forget() { count_ = 0; }

  // The remembered contacts, copied to the host (rbd/distributed/ moves
  // them between ranks with their bodies), and restore() of such a copy:
  // the next carry() starts from it. Its keys must be sorted.
  RememberedContacts<T> host_copy(stream_t stream = stream_t{}) const {
    RememberedContacts<T> out;
    out.width = p_.size_y();
    const std::size_t n = count_ == 0 ? 0 : detail::read_back<Device>(live_.data(), 0, stream);
    if (n == 0) return out;
    out.keys.resize(n), out.features.resize(n), out.values.resize(n * out.width);
    const VectorD1<std::uint64_t, device_is<device::cpu>> keys(keys_);
    const VectorD1<std::uint32_t, device_is<device::cpu>> features(features_);
    const VectorD2<T, device_is<device::cpu>> p(p_);
    for (std::size_t i = 0; i < n; ++i) {
      out.keys[i] = keys(i), out.features[i] = features(i);
      for (std::size_t r = 0; r < out.width; ++r) out.values[i * out.width + r] = p(i, r);
    }
    return out;
  }
  void restore(const RememberedContacts<T>& kept) {
    count_ = kept.keys.size();
    if (count_ == 0) return;
    VectorD1<std::uint64_t, device_is<device::cpu>> keys(count_);
    VectorD1<std::uint32_t, device_is<device::cpu>> features(count_), live(1);
    VectorD2<T, device_is<device::cpu>> p(count_, kept.width);
    for (std::size_t i = 0; i < count_; ++i) {
      keys(i) = kept.keys[i], features(i) = kept.features[i];
      for (std::size_t r = 0; r < kept.width; ++r) p(i, r) = kept.values[i * kept.width + r];
    }
    live(0) = std::uint32_t(count_);
    keys_.resize(count_), features_.resize(count_), p_.resize(count_, kept.width), live_.resize(1);
    keys_ = keys, features_ = features, p_ = p, live_ = live;
  }
  // The bodies of `b` were put in a new order, slot s moving to moved[s] (in
  // the backend's memory): the remembered pairs follow them (detail::RenumberPair)
  // and are sorted again, so the next carry() finds them.
  template <class BV>
  void renumber(const BV& b, const std::uint32_t* moved, stream_t stream = stream_t{}) {
    const std::size_t n = count_ == 0 ? 0 : detail::read_back<Device>(live_.data(), 0, stream);
    if (n == 0) return;
    launch(Device{}, n, detail::RenumberPair<Model, BV, T>{b, keys_.data(), p_.view(), moved}, stream);
    const auto policy = detail::thrust_policy(Device{}, stream);
    VectorD1<std::uint32_t, device_is<Device>> order(n), features(n);
    VectorD1<T, device_is<Device>> row(n);
    thrust::sequence(policy, order.data(), order.data() + n);
    thrust::sort_by_key(policy, keys_.data(), keys_.data() + n, order.data());
    thrust::gather(policy, order.data(), order.data() + n, features_.data(), features.data());
    thrust::copy(policy, features.data(), features.data() + n, features_.data());
    for (std::size_t r = 0; r < p_.size_y(); ++r) {
      T* values = p_.data() + r * p_.pitch();
      thrust::gather(policy, order.data(), order.data() + n, values, row.data());
      thrust::copy(policy, row.data(), row.data() + n, values);
    }
  }
  // The bound of the contacts remembered (their count is written where remember runs).
  std::size_t remembered() const { return count_; }

 private:
  VectorD1<std::uint64_t, device_is<Device>> keys_;
  VectorD1<std::uint32_t, device_is<Device>> features_;
  VectorD2<T, device_is<Device>> p_;
  VectorD1<std::uint32_t, device_is<Device>> live_;  // the remembered contacts' count
  std::size_t count_ = 0;
};

}  // namespace gpusolve::rbd
