// The accuracy figures every step reports, defined once: the largest
// interpenetration relative to the feature size, kinetic and potential energy.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/derived_fields.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"

namespace gpusolve::rbd {

// A step's accuracy figures: the largest penetration relative to the smaller
// feature size of the pair (feature_size: a radius, a box's smallest half extent), kinetic and potential energy of the moving bodies; and
// the number of contacts, which a step queued without a host wait knows only here.
template <class T>
struct StepFigures {
  T max_penetration, kinetic_energy, potential_energy;
  std::uint32_t contacts;
};

namespace detail {

// max(0, -gap) / min(feature_size a, feature_size b).
template <class BV, class CV, class T>
struct RelativePenetration {
  BV b;
  CV c;
  GPUSOLVE_HD T operator()(std::size_t i) const {
    const T depth = -c.phi0[i];
    if (!(depth > T(0))) return T(0);
    const T ra = feature_size(b, c.a[i]), rb = feature_size(b, c.b[i]);
    return depth / (ra < rb ? ra : rb);
  }
};

// 1/2 m v.v + 1/2 w_b.(I_b w_b) with w_b = R^T w, for moving bodies.
template <class BV, class T>
struct KineticEnergy {
  BV b;
  GPUSOLVE_HD T operator()(std::size_t k) const {
    if (!b.moving(k)) return T(0);
    const math::Vector3<T> v = math::load3<T>(b.v, k);
    const math::Vector3<T> wb = math::transpose(math::load9<T>(b.R, k)) * math::load3<T>(b.w, k);
    const math::Vector3<T> Iw = math::load9<T>(b.inertia, k) * wb;
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
    return -math::dot(g, math::load3<T>(b.pos, k)) / b.inv_mass[k];
  }
};

// The figures in one reduction over max(contacts' bound, bodies) indices.
template <class BV, class CV, class T>
struct StepFiguresOf {
  BV b;
  CV c;
  math::Vector3<T> g;
  GPUSOLVE_HD StepFigures<T> operator()(std::size_t i) const {
    StepFigures<T> f{};
    const std::size_t contacts = c.size();
    if (i == 0) f.contacts = std::uint32_t(contacts);
    if (i < contacts) f.max_penetration = RelativePenetration<BV, CV, T>{b, c}(i);
    if (i < b.size()) {
      f.kinetic_energy = KineticEnergy<BV, T>{b}(i);
      f.potential_energy = PotentialEnergy<BV, T>{b, g}(i);
    }
    return f;
  }
};

// Index i's own update (`before`: body i's, contact i's, nothing else's), then
// index i's figures: an update and the figures after it in one pass.
template <class Before, class Figures>
struct AfterEach {
  Before before;
  Figures figures;
  GPUSOLVE_HD auto operator()(std::size_t i) const {
    before(i);
    return figures(i);
  }
};

struct CombineFigures {
  template <class T>
  GPUSOLVE_HD StepFigures<T> operator()(const StepFigures<T>& x, const StepFigures<T>& y) const {
    return StepFigures<T>{x.max_penetration < y.max_penetration ? y.max_penetration : x.max_penetration,
                          x.kinetic_energy + y.kinetic_energy, x.potential_energy + y.potential_energy,
                          x.contacts + y.contacts};
  }
};

}  // namespace detail

// Queues the figures of bodies b and contacts c into *out, memory of the
// backend, in one reduction (no host wait).
template <class Device, class T, class BV, class CV>
void step_figures_into(detail::DeviceAlgorithms<Device>& algorithms, const BV& b, const CV& c,
                       const math::Vector3<T>& gravity, StepFigures<T>* out, stream_t stream = stream_t{}) {
  const std::size_t n = c.bound() > b.size() ? c.bound() : b.size();
  algorithms.reduce_into(n, detail::StepFiguresOf<BV, CV, T>{b, c, gravity}, StepFigures<T>{}, detail::CombineFigures{},
                         out, stream);
}

// The update `before` of every index i < max(contacts, bodies) (e.g. the
// step's move: body i's own state only), then the figures of the state it
// leaves, in one pass over the indices.
template <class Device, class T, class BV, class CV, class Before>
void step_figures_after(detail::DeviceAlgorithms<Device>& algorithms, const Before& before, const BV& b, const CV& c,
                        const math::Vector3<T>& gravity, StepFigures<T>* out, stream_t stream = stream_t{}) {
  const std::size_t n = c.bound() > b.size() ? c.bound() : b.size();
  using Figures = detail::StepFiguresOf<BV, CV, T>;
  algorithms.evaluate_and_reduce(n, detail::AfterEach<Before, Figures>{before, Figures{b, c, gravity}},
                                 StepFigures<T>{}, detail::CombineFigures{}, out, stream);
}

}  // namespace gpusolve::rbd
