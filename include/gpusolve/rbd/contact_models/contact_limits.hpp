// ContactLimits: the bounds a contact model projects its impulse rows onto,
// read once per contact from the contacts' fields the model stores.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// mu bounds the tangential impulse by mu x_n; spin (a length) the torsional
// impulse about n by spin x_n; roll (a length) the rolling impulse about the
// tangents by roll x_n (Chrono's rolling and spinning friction). A model reads
// only the bounds of the rows it has.
template <class T>
struct ContactLimits {
  T mu = T(0), spin = T(0), roll = T(0);
};

// Contact i's limits from the contacts' view c: mu only for a model with
// friction, spin and roll only for one with angular rows, so that a model
// without them loads nothing more than before.
template <class Model, class T, class CV>
GPUSOLVE_HD ContactLimits<T> limits_of(const CV& c, std::size_t i) {
  ContactLimits<T> k;
  if constexpr (Model::friction) k.mu = c.mu[i];
  if constexpr (Model::rows > Model::linear_rows) k.spin = c.spin[i], k.roll = c.roll[i];
  return k;
}

}  // namespace gpusolve::rbd
