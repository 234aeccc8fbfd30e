// Contact models (thesis Eq. 6-8): how many impulse rows a contact has and how they are projected.
#pragma once

// A contact model is a compile-time policy with
//   static constexpr std::size_t rows;                       // impulse rows per contact
//   static constexpr bool friction;                          // tangents and mu are stored
//   template <class T> static void project(T* x, T mu);      // onto the admissible set
// Row 0 is always the normal impulse, rows 1 and 2 (if any) the tangential ones
// along the contact's t and o. Every solver works with every model; a scene
// picks the cheapest one it needs (1 row instead of 3 without friction).
#include "gpusolve/rbd/contact_models/cone_friction.hpp"
#include "gpusolve/rbd/contact_models/frictionless.hpp"
#include "gpusolve/rbd/contact_models/pyramid_friction.hpp"
