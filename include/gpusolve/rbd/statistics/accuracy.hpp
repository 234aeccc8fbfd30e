// The accuracy figures every step reports, defined once: the largest
// interpenetration relative to the radius, kinetic and potential energy.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/solvers/contact_kernels.hpp"
#include "gpusolve/rbd/detail/reduce.hpp"

namespace gpusolve::rbd {

namespace detail {

// max(0, -gap) / min(radius a, radius b): planes have an infinite radius, so a
// sphere on a plane is measured against the sphere.
template <class BV, class CV, class T>
struct RelativePenetration {
  BV b;
  CV c;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    const T depth = -c.phi0[i];
    if (!(depth > T(0))) return T(0);
    const T ra = b.radius[c.a[i]], rb = b.radius[c.b[i]];
    return depth / (ra < rb ? ra : rb);
  }
};

// 1/2 m v.v + 1/2 w_b.(I_b w_b) with w_b = R^T w, for moving bodies.
template <class BV, class T>
struct KineticEnergy {
  BV b;
  GPUSOLVE_HD T operator()(std::size_t k) const {
    if (!b.moving(k)) return T(0);
    const math::Vector3<T> v = load3<T>(b.v, k);
    const math::Vector3<T> wb = math::transpose(load9<T>(b.R, k)) * load3<T>(b.w, k);
    const math::Vector3<T> Iw = load9<T>(b.inertia, k) * wb;
    return T(0.5) * (math::dot(v, v) / b.inv_mass[k] + math::dot(wb, Iw));
  }
};

// -m g.x for moving bodies: zero at the origin.
template <class BV, class T>
struct PotentialEnergy {
  BV b;
  math::Vector3<T> g;
  GPUSOLVE_HD T operator()(std::size_t k) const {
    if (!b.moving(k)) return T(0);
    return -math::dot(g, load3<T>(b.pos, k)) / b.inv_mass[k];
  }
};

}  // namespace detail

// Largest interpenetration of the contacts relative to the smaller radius of the pair.
template <class Device, class T, class BV, class CV>
T max_relative_penetration(const BV& b, const CV& c, stream_t stream = stream_t{}) {
  return max_over(Device{}, c.size(), detail::RelativePenetration<BV, CV, T>{b, c}, T(0), stream);
}

template <class Device, class BV, class T>
T kinetic_energy(const BV& b, stream_t stream = stream_t{}) {
  return sum_over(Device{}, b.size(), detail::KineticEnergy<BV, T>{b}, T(0), stream);
}

template <class Device, class BV, class T>
T potential_energy(const BV& b, const math::Vector3<T>& gravity, stream_t stream = stream_t{}) {
  return sum_over(Device{}, b.size(), detail::PotentialEnergy<BV, T>{b, gravity}, T(0), stream);
}

}  // namespace gpusolve::rbd
