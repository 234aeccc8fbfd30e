// BodySet: a host-side, growable list of Body records with validating builders.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "gpusolve/rbd/bodies/body.hpp"
#include "gpusolve/rbd/bodies/mass_properties.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"

namespace gpusolve::rbd {

// The host array of a user's engine. Indices are stable until the BodyManager
// compacts removed bodies. Every builder validates and throws InvalidBodyError.
template <class T = float>
class BodySet {
 public:
  using Vec = std::array<T, 3>;

  using Quat = std::array<T, 4>;
  static constexpr Quat unrotated{1, 0, 0, 0};

  // A moving sphere. principal_inertia (body frame, diagonal) defaults to the
  // solid sphere 2/5 m r^2; give it to model a non-isotropic body.
  std::size_t add_sphere(const Vec& pos, T radius, T mass, const Vec& principal_inertia = {}) {
    require_positive(radius, "radius");
    const bool given = principal_inertia[0] != 0 || principal_inertia[1] != 0 || principal_inertia[2] != 0;
    return add_moving(sphere, {radius, 0, 0, 0}, pos, unrotated, mass,
                      given ? principal_inertia : solid_sphere(radius, mass).inertia);
  }
  // A sphere that never moves (an obstacle).
  std::size_t add_fixed_sphere(const Vec& pos, T radius) { return add_fixed(sphere, {radius, 0, 0, 0}, pos, unrotated); }

  // A moving solid box with half extents h along its body axes, rotated by
  // the unit quaternion q = (w, x, y, z). For a density rho, mass = rho * 8 h_x h_y h_z
  // (solid_box(h, m).volume).
  std::size_t add_box(const Vec& pos, const Vec& h, T mass, const Quat& q = unrotated) {
    for (T x : h) require_positive(x, "half_extents");
    return add_moving(box, {h[0], h[1], h[2], 0}, pos, q, mass, solid_box(h, mass).inertia);
  }
  // A box that never moves.
  std::size_t add_fixed_box(const Vec& pos, const Vec& h, const Quat& q = unrotated) {
    return add_fixed(box, {h[0], h[1], h[2], 0}, pos, q);
  }

  // A moving solid capsule: the points within `radius` of the segment of half
  // length `half_length` along the body x axis, rotated by q.
  std::size_t add_capsule(const Vec& pos, T radius, T half_length, T mass, const Quat& q = unrotated) {
    require_positive(radius, "radius");
    require_positive(half_length, "half_length");
    return add_moving(capsule, {radius, half_length, 0, 0}, pos, q, mass,
                      solid_capsule(radius, half_length, mass).inertia);
  }
  // A capsule that never moves.
  std::size_t add_fixed_capsule(const Vec& pos, T radius, T half_length, const Quat& q = unrotated) {
    return add_fixed(capsule, {radius, half_length, 0, 0}, pos, q);
  }

  // The fixed half-space n.x <= d; n need not be normalised but must not be zero.
  std::size_t add_plane(const Vec& n, T d) {
    const std::size_t index = bodies_.size();
    const T len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0) || !std::isfinite(len))
      throw InvalidBodyError(index, "normal", "must be finite and of non-zero length");
    Body<T> b;
    b.status = fixed;
    b.shape = plane;
    b.shape_param = {n[0] / len, n[1] / len, n[2] / len, d};
    b.pos = {b.shape_param[0] * d, b.shape_param[1] * d, b.shape_param[2] * d};
    return add(b);
  }

  // Appends any validated record; returns its index.
  std::size_t add(const Body<T>& b) {
    validate_body(b, bodies_.size());
    bodies_.push_back(b);
    return bodies_.size() - 1;
  }

  // Validates every record (after the user's engine changed them in place).
  void validate() const {
    for (std::size_t i = 0; i < bodies_.size(); ++i) validate_body(bodies_[i], i);
  }

  std::size_t size() const { return bodies_.size(); }
  Body<T>& operator[](std::size_t i) { return bodies_[i]; }
  const Body<T>& operator[](std::size_t i) const { return bodies_[i]; }
  std::vector<Body<T>>& records() { return bodies_; }
  const std::vector<Body<T>>& records() const { return bodies_; }

 private:
  void require_positive(T x, const char* field) const {
    if (!(x > 0) || !std::isfinite(x)) throw InvalidBodyError(bodies_.size(), field, "must be positive and finite");
  }
  // A moving body of the given principal inertia (body frame, diagonal).
  std::size_t add_moving(ShapeKind kind, const std::array<T, shape_param_rows>& param, const Vec& pos, const Quat& q,
                         T mass, const Vec& principal_inertia) {
    require_positive(mass, "mass");
    Body<T> b;
    b.shape = kind;
    b.shape_param = param;
    b.pos = pos;
    b.q = q;
    b.inv_mass = T(1) / mass;
    for (int k = 0; k < 3; ++k) {
      const T I = principal_inertia[k];
      if (!(I > 0) || !std::isfinite(I))
        throw InvalidBodyError(bodies_.size(), "inertia", "diagonal must be positive and finite");
      b.inertia[4 * k] = I;
      b.inv_inertia_body[4 * k] = T(1) / I;
    }
    return add(b);
  }
  std::size_t add_fixed(ShapeKind kind, const std::array<T, shape_param_rows>& param, const Vec& pos, const Quat& q) {
    Body<T> b;
    b.status = fixed;
    b.shape = kind;
    b.shape_param = param;
    b.pos = pos;
    b.q = q;
    return add(b);
  }

  std::vector<Body<T>> bodies_;
};

}  // namespace gpusolve::rbd
