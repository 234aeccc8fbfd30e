// ContactSettings: how contacts are generated and what they carry: the margin
// within which a gap becomes a contact, the share of a penetration corrected
// per step, the default material's friction, restitution and rolling and
// spinning resistance, friction anchors.
#pragma once

#include <cmath>
#include <cstddef>

#include "gpusolve/rbd/settings/setting_error.hpp"

namespace gpusolve::rbd {

template <class T>
struct ContactSettings {
  // A contact is kept while its gap is below the margin (m): a body moving up to
  // about a margin per step is caught before it sinks in. Scale it with the
  // scene; the default is a tenth of a unit radius (docs/tuning/contacts.md).
  T margin = T(0.1);
  T correction = T(0.2);  // fraction of a penetration removed per step, in (0, 1]
  // The world's default material (id 0, bodies/materials.hpp): friction coefficient
  // (models with friction) and coefficient of restitution of its contacts.
  T friction = T(0.5);
  T restitution = T(0);
  // Its rolling and spinning resistance (m, bodies/materials.hpp): nonzero only
  // in a World whose contact model has angular rows (ConeRollingFriction).
  T rolling = T(0);
  T spinning = T(0);
  // A contact bounces (restitution) only where its bodies approach faster than
  // this (m/s): slower impacts, as of a body coming to rest, do not (Box2D v3's
  // restitution threshold, 1 m/s).
  T bounce_threshold = T(1);
  // Static friction holds a sticking contact's two points together: the
  // friction rows also correct their slip, by `correction` per step
  // (solvers/friction_anchors.hpp), so that a standing structure does not
  // creep. Applied where the scene holds boxes, capsules or compounds and the
  // warm start is on (it keeps the anchors); scenes of spheres and planes do
  // not pay for it.
  bool friction_anchors = true;
  // The room per body the contact list starts with. A step that finds more
  // grows it by half again (an unattended step is then held and queued again,
  // World::steps_requeued); a settled sphere pile holds 1.5 to 3 per body, a
  // pile of boxes about 5 (docs/memory.md).
  std::size_t contacts_per_body = 2;

  // Throws InvalidArgumentError naming the first offending field.
  void validate() const {
    if (!(margin >= 0) || !std::isfinite(margin)) detail::bad_setting("margin", "must be non-negative and finite");
    if (!(correction > 0 && correction <= 1)) detail::bad_setting("correction", "must lie in (0, 1]");
    if (!(friction >= 0) || !std::isfinite(friction)) detail::bad_setting("friction", "must be non-negative and finite");
    if (!(restitution >= 0 && restitution <= 1)) detail::bad_setting("restitution", "must lie in [0, 1]");
    if (!(rolling >= 0) || !std::isfinite(rolling)) detail::bad_setting("rolling", "must be non-negative and finite");
    if (!(spinning >= 0) || !std::isfinite(spinning)) detail::bad_setting("spinning", "must be non-negative and finite");
    if (contacts_per_body == 0) detail::bad_setting("contacts_per_body", "must be at least 1");
    if (!(bounce_threshold >= 0) || !std::isfinite(bounce_threshold))
      detail::bad_setting("bounce_threshold", "must be non-negative and finite");
  }
};

}  // namespace gpusolve::rbd
