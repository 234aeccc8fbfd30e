// BodySet: a host-side, growable list of Body records with validating builders.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "gpusolve/rbd/bodies/body.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"

namespace gpusolve::rbd {

// The host array of a user's engine. Indices are stable until the BodyManager
// compacts removed bodies. Every builder validates and throws InvalidBodyError.
template <class T = float>
class BodySet {
 public:
  using Vec = std::array<T, 3>;

  // A moving sphere. principal_inertia (body frame, diagonal) defaults to the
  // solid sphere 2/5 m r^2; give it to model a non-isotropic body.
  std::size_t add_sphere(const Vec& pos, T radius, T mass, const Vec& principal_inertia = {}) {
    const std::size_t index = bodies_.size();
    if (!(radius > 0) || !std::isfinite(radius))
      throw InvalidBodyError(index, "radius", "must be positive and finite");
    if (!(mass > 0) || !std::isfinite(mass))
      throw InvalidBodyError(index, "mass", "must be positive and finite");
    Body<T> b;
    b.shape = sphere;
    b.shape_param = {radius, 0, 0, 0};
    b.pos = pos;
    b.inv_mass = T(1) / mass;
    const T solid = T(2) / T(5) * mass * radius * radius;
    for (int k = 0; k < 3; ++k) {
      const T I = principal_inertia[0] == 0 && principal_inertia[1] == 0 &&
                          principal_inertia[2] == 0
                      ? solid
                      : principal_inertia[k];
      if (!(I > 0) || !std::isfinite(I))
        throw InvalidBodyError(index, "inertia", "diagonal must be positive and finite");
      b.inertia[4 * k] = I;
      b.inv_inertia_body[4 * k] = T(1) / I;
    }
    return add(b);
  }

  // A sphere that never moves (an obstacle).
  std::size_t add_fixed_sphere(const Vec& pos, T radius) {
    Body<T> b;
    b.status = fixed;
    b.shape = sphere;
    b.shape_param = {radius, 0, 0, 0};
    b.pos = pos;
    return add(b);
  }

  // A fixed box with half extents h, rotated by the unit quaternion q = (w, x, y, z).
  std::size_t add_box(const Vec& pos, const Vec& h, const std::array<T, 4>& q = {1, 0, 0, 0}) {
    Body<T> b;
    b.status = fixed;
    b.shape = box;
    b.shape_param = {h[0], h[1], h[2], 0};
    b.pos = pos;
    b.q = q;
    return add(b);
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
  std::vector<Body<T>> bodies_;
};

}  // namespace gpusolve::rbd
