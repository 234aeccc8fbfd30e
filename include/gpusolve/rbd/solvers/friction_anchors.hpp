// Friction anchors: where a contact sticks, its two material points stay
// together. While a contact sticks, the tangential displacement of its two
// points since it began to stick (Contacts::slip) is kept from step to step,
// and the friction rows correct it by the share per step the normal row
// corrects a penetration (CalcNextPhi). A friction solve stopped short of
// convergence leaves a small tangential velocity at every sticking point,
// which without anchors adds up from step to step: a standing structure
// creeps (measured in docs/shapes.md). The displacement is summed
// from the relative velocity at the contact point, so that a body rolling
// without slipping moves no anchor. Bullet keeps friction anchors for the
// same reason (btCollisionObject::CF_HAS_FRICTION_ANCHOR).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/contact_models/contact_limits.hpp"

namespace gpusolve::rbd::detail {

// The values the warm start keeps per contact for its anchor: the slip as a
// world vector, NaN where the contact did not stick.
inline constexpr std::size_t anchor_values = 3;

// Whether impulse x sticks: its friction rows lie inside the friction limit
// (a thousandth short of it, so that a contact sliding on the limit counts as
// sliding), or it pushes nothing.
template <class Model, class T>
GPUSOLVE_HD bool sticks(const T (&x)[Model::rows], const ContactLimits<T>& limits) {
  static_assert(Model::linear_rows == 3, "sticks: a model with friction rows");
  if (!(x[0] > T(0))) return true;
  T y[Model::rows];
  for (std::size_t r = 0; r < Model::rows; ++r) y[r] = x[r];
  y[1] /= T(0.999), y[2] /= T(0.999);
  Model::project(y, limits);
  return y[1] == x[1] / T(0.999) && y[2] == x[2] / T(0.999);
}

// Writes contact i's anchor for the next step into p(i, first ...): its slip
// as a world vector where its impulse x sticks, none (NaN) where it slides.
template <class Model, class CV, class P, class T>
GPUSOLVE_HD void remember_anchor(const CV& c, std::size_t i, const T (&x)[Model::rows], const P& p,
                                 std::size_t first) {
  const bool keep = sticks<Model, T>(x, limits_of<Model, T>(c, i));
  const math::Vector3<T> s = math::load3<T>(c.t, i) * c.slip(i, 0) + math::load3<T>(c.o, i) * c.slip(i, 1);
  for (std::size_t k = 0; k < anchor_values; ++k) p(i, first + k) = keep ? s[k] : std::numeric_limits<T>::quiet_NaN();
}

// Sets contact i's slip along t and o: where the point stuck in the last step
// (`kept`, its slip as a world vector), that slip plus the last step's
// displacement of the two points at the contact, the relative velocity the
// step ended with times dt; else zero (a new or sliding point).
template <class BV, class CV, class T>
GPUSOLVE_HD void carry_anchor(const BV& b, const CV& c, std::size_t i, const T* kept, T dt) {
  math::Vector3<T> s;
  if (kept != nullptr && kept[0] == kept[0]) {
    const std::uint32_t ia = c.a[i], ib = c.b[i];
    const math::Vector3<T> ua = math::load3<T>(b.v, ia) + math::load3<T>(b.w, ia) % math::load3<T>(c.ra, i);
    const math::Vector3<T> ub = math::load3<T>(b.v, ib) + math::load3<T>(b.w, ib) % math::load3<T>(c.rb, i);
    s = math::Vector3<T>(kept[0], kept[1], kept[2]) + (ua - ub) * dt;
  }
  c.slip(i, 0) = math::dot(s, math::load3<T>(c.t, i));
  c.slip(i, 1) = math::dot(s, math::load3<T>(c.o, i));
}

}  // namespace gpusolve::rbd::detail
