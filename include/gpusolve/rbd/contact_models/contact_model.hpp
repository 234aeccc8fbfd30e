// Contact models (thesis Eq. 6-8): how many impulse rows a contact has, which
// of them are linear and which angular, and how they are projected.
#pragma once

// A contact model is a compile-time policy with
//   static constexpr std::size_t rows;         // impulse rows per contact
//   static constexpr std::size_t linear_rows;  // rows 0 .. linear_rows-1: forces at the contact point
//   static constexpr bool friction;            // tangents and mu are stored
//   template <class T> static void project(T* x, const ContactLimits<T>&);  // onto the admissible set
// Row 0 is always the normal impulse, rows 1 and 2 (if any) the tangential ones
// along the contact's t and o. Rows from linear_rows on are angular impulses
// about n, t, o in turn (torsion, then rolling), whose bounds (spin, roll) the
// contacts store only for such a model. Every solver works with every model but
// AcceleratedCG (ConeFriction only); a scene picks the cheapest one it needs
// (1 row instead of 3 without friction, 3 instead of 6 without rolling).
#include "gpusolve/rbd/contact_models/cone_friction.hpp"
#include "gpusolve/rbd/contact_models/cone_rolling_friction.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"
#include "gpusolve/rbd/contact_models/frictionless.hpp"
#include "gpusolve/rbd/contact_models/pyramid_friction.hpp"
