// BodyManager: keeps a device copy of a host BodySet in sync (thesis 5.1.2).
#pragma once

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <vector>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocation_label.hpp"
#include "gpusolve/memory/copy.hpp"
#include "gpusolve/rbd/bodies/bodies.hpp"
#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/bodies/derived_fields.hpp"
#include "gpusolve/math/quaternion.hpp"
#include "gpusolve/math/rotation.hpp"

namespace gpusolve::rbd {

// What one synchronisation to the device did.
struct SyncReport {
  std::size_t bodies = 0;     // bodies on the device afterwards
  std::size_t full_from = 0;  // every field of bodies [full_from, bodies) was copied
  bool rebuilt = false;       // removed bodies were compacted away (indices changed)
};

inline constexpr std::size_t default_rebuild_threshold = 256;
// Bodies packed, or unpacked, per pass of a sync through the host staging
// store: the store holds this many, not one record per body (282 bytes each).
inline constexpr std::size_t sync_chunk = std::size_t(1) << 16;

// For users whose engine keeps its bodies on the host, in a BodySet. Changes
// announced by bodyAdded/bodyRemoved are applied lazily, at the next sync.
// Removed bodies are only marked status = removed until `rebuild_threshold` of
// them have accumulated; then the BodySet is compacted (later bodies move down,
// keeping their order) and everything is copied again. Bodies in front of the
// first added one keep their shape and mass data on the device.
// The device copy may hold the bodies in an order of its own (reordered(): a
// World keeps them in spatial order); slot() and body() map between a body's
// index in the BodySet and its slot on the device, and every sync goes through
// them, so the BodySet's indices always name the same bodies. A compaction
// (removed bodies past the threshold) starts again from the BodySet's order.
// Device may be device::cpu, which makes the device copy a second host copy.
// `compiled`: the shape kinds its user was compiled for (World's Shapes); a
// body of another kind (or a compound with such a part) is refused at sync.
template <class Device, class T = float>
class BodyManager {
 public:
  explicit BodyManager(BodySet<T>& host, std::size_t rebuild_threshold = default_rebuild_threshold,
                       ShapeMask compiled = all_shapes)
      : host_(host), threshold_(rebuild_threshold > 0 ? rebuild_threshold : 1), compiled_(compiled) {}

  // Body `index` of the BodySet is new (or was replaced): copy all of it next sync.
  void bodyAdded(std::size_t index) { added_.push_back(index); }
  // Body `index` of the BodySet is gone: marked removed at the next sync.
  void bodyRemoved(std::size_t index) { removed_.push_back(index); }

  // Applies pending additions and removals, then copies the per-step fields
  // (status, position, orientation, velocities, forces, torques and what
  // derives from them) of every body, and all fields of added bodies.
  SyncReport syncDevice(stream_t stream = stream_t{}) { return sync(false, stream); }
  // Same, but copies every field of every body.
  SyncReport syncDeviceFull(stream_t stream = stream_t{}) { return sync(true, stream); }

  // Copies the device's per-step state back into the BodySet records
  // (position, orientation, velocities, forces, torques, motion). Synchronous.
  void syncHost(stream_t stream = stream_t{}) {
    const std::size_t n = device_.size();
    if (n != host_.size())
      throw SizeMismatchError("gpusolve: BodyManager::syncHost: the BodySet changed size since the "
                              "last syncDevice; announce changes with bodyAdded/bodyRemoved and sync");
    for (std::size_t c = 0; c < n; c += sync_chunk) {
      const std::size_t e = std::min(n, c + sync_chunk);
      staging_.resize(e - c);
      copy_fields(staging_, 0, device_, c, e - c, true, stream);
      for (std::size_t k = c; k < e; ++k) unpack(body(k), k - c);
    }
  }

  // The device bodies were put in `order` (their slot k now holds what slot
  // order[k] held; SpatialOrder): the slots of the BodySet's bodies follow.
  void reordered(const std::vector<std::uint32_t>& order) {
    const std::size_t n = device_.size();
    if (order.size() != n)
      throw SizeMismatchError("gpusolve: BodyManager::reordered: the order must name every body's slot once");
    std::vector<std::uint32_t> body_of(n);
    for (std::size_t k = 0; k < n; ++k) body_of[k] = std::uint32_t(body(order[k]));
    slot_of_.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) slot_of_[body_of[k]] = std::uint32_t(k);
    body_of_ = std::move(body_of);
  }
  // The device slot of the BodySet's body i, and the BodySet index of slot k.
  std::size_t slot(std::size_t i) const { return slot_of_.empty() ? i : slot_of_[i]; }
  std::size_t body(std::size_t k) const { return body_of_.empty() ? k : body_of_[k]; }

  Bodies<Device, T>& device() { return device_; }
  const BodySet<T>& host() const { return host_; }
  std::size_t rebuild_threshold() const { return threshold_; }
  std::size_t removed_count() const { return removed_count_; }

 private:
  // The kinds of body i (a compound's parts' too); throws InvalidBodyError
  // naming the body where one is not among the kinds compiled in.
  ShapeMask require_compiled(std::size_t i) const {
    const Body<T>& b = host_.records()[i];
    ShapeMask kinds = shape_bit(b.shape);
    if (b.shape == compound)
      for (std::size_t k = 0; k < std::size_t(b.shape_param[0]); ++k)
        kinds |= shape_bit(host_.parts()[b.first_part + k].shape);
    if (kinds & ~compiled_) {
      std::ostringstream os;
      os << "this World was not compiled for";
      for (int k = 0; k < shape_kinds; ++k)
        if (kinds & ~compiled_ & shape_bit(ShapeKind(k))) os << ' ' << shape_name(std::uint8_t(k));
      os << "; give World the Shapes it needs (all_shapes holds every kind)";
      throw InvalidBodyError(i, "shape", os.str());
    }
    return kinds;
  }

  SyncReport sync(bool full, stream_t stream) {
    const memory::AllocationLabel label("bodies");
    auto& recs = host_.records();
    SyncReport rep;
    for (std::size_t i : removed_) {
      check_index(i, "bodyRemoved");
      if (recs[i].status != removed) ++removed_count_;
      recs[i].status = removed;
    }
    const std::size_t before = device_.size();
    std::size_t first = full ? 0 : before;  // bodies past the old end are new
    for (std::size_t i : added_) first = std::min(first, check_index(i, "bodyAdded"));
    // A body replaced in place sits in a slot of its own order: copy all.
    if (!slot_of_.empty() && first < before) first = 0;
    added_.clear();
    removed_.clear();
    if (removed_count_ >= threshold_) {
      recs.erase(std::remove_if(recs.begin(), recs.end(), [](const Body<T>& b) { return b.status == removed; }),
                 recs.end());
      removed_count_ = 0;
      rep.rebuilt = true;
      first = 0;
      slot_of_.clear(), body_of_.clear();  // the BodySet's order again
    }
    const std::size_t n = recs.size();
    if (!slot_of_.empty())  // new bodies take the slots past the old end, in order
      for (std::size_t i = before; i < n; ++i) slot_of_.push_back(std::uint32_t(i)), body_of_.push_back(std::uint32_t(i));
    ShapeMask shapes = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (recs[i].status != removed) {
        host_.validate(i);
        shapes |= require_compiled(i);
      }
    // Growth reallocates (contents lost), so double to keep appends amortised.
    if (n > device_.capacity()) {
      device_.resize(std::max(n, 2 * device_.capacity()));
      first = 0;
    }
    device_.resize(n);
    device_.shapes = shapes;
    first = std::min(first, n);
    // Slot by slot, sync_chunk at a time: every field packed (the derived ones
    // need shape and mass), the per-step ones copied below `first`, all from it.
    for (std::size_t c = 0; c < n; c += sync_chunk) {
      const std::size_t e = std::min(n, c + sync_chunk), split = std::clamp(first, c, e);
      staging_.resize(e - c);
      for (std::size_t k = c; k < e; ++k) pack(body(k), k - c);
      update_derived(device::cpu{}, staging_.view(), 0, e - c);
      copy_fields(device_, c, staging_, 0, split - c, false, stream);
      copy_fields(device_, split, staging_, split - c, e - split, true, stream);
    }
    if (full || parts_.size() != host_.parts().size()) copy_parts();
    device_.materials.copy_from(host_.materials());
    rep.bodies = n;
    rep.full_from = first;
    return rep;
  }

  std::size_t check_index(std::size_t i, const char* who) const {
    if (i >= host_.size()) {
      std::ostringstream os;
      os << "gpusolve: BodyManager::" << who << "(" << i << "): the BodySet has " << host_.size()
         << " bodies";
      throw InvalidArgumentError(os.str());
    }
    return i;
  }

  // Copies `count` bodies from slot `from` of src to slot `to` of dst: the
  // per-step fields, or all fields if `all`. Synchronous, so src may be reused.
  template <class Dst, class Src>
  static void copy_fields(Dst& dst, std::size_t to, Src& src, std::size_t from, std::size_t count, bool all,
                          stream_t stream) {
    if (count == 0) return;
    zip_fields(dst, src, [&](auto& d, auto& s, std::size_t rows, bool per_step) {
      if (!all && !per_step) return;
      using E = typename std::remove_reference_t<decltype(d)>::value_type;
      using To = typename std::remove_reference_t<decltype(d)>::memory_kind;
      using From = typename std::remove_reference_t<decltype(s)>::memory_kind;
      memory::copy_rows<To, From>(d.data() + to, d.pitch() * sizeof(E), s.data() + from, s.pitch() * sizeof(E),
                                  count * sizeof(E), rows, false, stream);
    });
  }

  // Writes record i into slot k of the staging store.
  void pack(std::size_t i, std::size_t k) {
    const Body<T>& r = host_[i];
    auto& s = staging_;
    s.status(k) = r.status;
    for (std::size_t c = 0; c < 3; ++c) {
      s.pos(k, c) = r.pos[c];
      s.v(k, c) = r.v[c];
      s.w(k, c) = r.w[c];
      s.force(k, c) = r.force[c];
      s.torque(k, c) = r.torque[c];
    }
    for (std::size_t c = 0; c < 4; ++c) s.q(k, c) = r.q[c];
    s.motion(k) = r.motion;
    s.shape(k) = r.shape;
    for (std::size_t c = 0; c < shape_param_rows; ++c) s.shape_param(k, c) = r.shape_param[c];
    s.inv_mass(k) = r.inv_mass;
    s.first_part(k) = r.first_part;
    s.material(k) = r.material;
    for (std::size_t c = 0; c < 9; ++c) {
      s.inertia(k, c) = r.inertia[c];
      s.inv_inertia_body(k, c) = r.inv_inertia_body[c];
    }
  }

  // The BodySet's parts, rotations from their quaternions, to the device (all
  // of them: parts only ever grow, and a scene holds few).
  void copy_parts() {
    const auto& parts = host_.parts();
    auto& s = parts_;
    s.resize(parts.size());
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const Part<T>& part = parts[k];
      s.shape(k) = part.shape;
      for (std::size_t c = 0; c < shape_param_rows; ++c) s.shape_param(k, c) = part.shape_param[c];
      for (std::size_t c = 0; c < 3; ++c) s.pos(k, c) = part.pos[c];
      const auto R = math::to_rotation_matrix(math::Quaternion<T>(part.q[0], part.q[1], part.q[2], part.q[3]));
      for (std::size_t c = 0; c < 9; ++c) s.R(k, c) = R[c];
      s.material(k) = part.material;
    }
    device_.parts = s;
  }

  // Reads record i from slot k of the staging store.
  void unpack(std::size_t i, std::size_t k) {
    Body<T>& r = host_[i];
    const auto& s = staging_;
    for (std::size_t c = 0; c < 3; ++c) {
      r.pos[c] = s.pos(k, c);
      r.v[c] = s.v(k, c);
      r.w[c] = s.w(k, c);
      r.force[c] = s.force(k, c);
      r.torque[c] = s.torque(k, c);
    }
    for (std::size_t c = 0; c < 4; ++c) r.q[c] = s.q(k, c);
    r.motion = s.motion(k);
  }

  BodySet<T>& host_;
  std::size_t threshold_;
  ShapeMask compiled_;
  std::size_t removed_count_ = 0;
  std::vector<std::size_t> added_, removed_;
  std::vector<std::uint32_t> slot_of_, body_of_;  // empty: slot i holds body i
  Bodies<device::cpu, T> staging_;  // up to sync_chunk bodies on their way to or from the device
  Parts<device::cpu, T> parts_;     // the parts last copied to the device
  Bodies<Device, T> device_;
};

}  // namespace gpusolve::rbd
