// BodySet: a host-side, growable list of Body records with validating builders.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "gpusolve/rbd/bodies/body.hpp"
#include "gpusolve/rbd/bodies/compound_type.hpp"
#include "gpusolve/rbd/bodies/mass_properties.hpp"
#include "gpusolve/rbd/bodies/materials.hpp"
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

  // A compound type (a clump template): its parts stored once in parts(),
  // shared by every body add_compound(pos, type, q) makes. The mass is shared
  // by the parts' volumes and the inertia summed over them by parallel axes
  // (solid_compound), so overlapping parts count twice: for those, give the
  // mass and inertia outright (below). The parts are moved so that the type's
  // frame lies at its centre of mass. Errors name the index the next body takes.
  CompoundType<T> add_compound_type(const std::vector<Part<T>>& parts, T mass) {
    require_positive(mass, "mass");
    require_parts(parts);
    const CompoundProperties<T> c = solid_compound(parts, mass);
    return store_type(parts, mass, c.inertia, c.centre);
  }
  // A compound type of a given mass and principal inertia (as DEM-Engine's
  // clump templates take them): the parts placed relative to the centre of
  // mass, along the principal axes, whatever they overlap.
  CompoundType<T> add_compound_type(const std::vector<Part<T>>& parts, T mass, const Vec& principal_inertia) {
    require_positive(mass, "mass");
    for (T x : principal_inertia) require_positive(x, "inertia");
    require_parts(parts);
    std::array<T, 9> inertia{};
    for (int k = 0; k < 3; ++k) inertia[4 * k] = principal_inertia[k];
    return store_type(parts, mass, inertia, Vec{});
  }
  // A moving compound of the type: the origin of the frame its parts were
  // given in lies at `pos`, turned by q; the body's centre (Body::pos) is the
  // centre of mass.
  std::size_t add_compound(const Vec& pos, const CompoundType<T>& type, const Quat& q = unrotated) {
    require_positive(type.mass, "mass");
    detail::require_unit(q, bodies_.size(), "q");
    Body<T> b = compound_record(pos, type, q);
    b.status = active;
    b.inv_mass = T(1) / type.mass;
    b.inertia = type.inertia;
    b.inv_inertia_body = type.inv_inertia;
    return add(b);
  }
  // A compound of the type that never moves.
  std::size_t add_fixed_compound(const Vec& pos, const CompoundType<T>& type, const Quat& q = unrotated) {
    detail::require_unit(q, bodies_.size(), "q");
    return add(compound_record(pos, type, q));
  }

  // A moving compound (pe's Union) with parts of its own: one rigid body made
  // of sphere, box and capsule parts, the type add_compound_type(parts, mass)
  // placed as add_compound(pos, type, q) places it.
  std::size_t add_compound(const Vec& pos, const std::vector<Part<T>>& parts, T mass, const Quat& q = unrotated) {
    return with_own_parts([&] { return add_compound(pos, add_compound_type(parts, mass), q); });
  }
  // A compound with parts of its own that never moves (its centre is its
  // parts' centre of volume).
  std::size_t add_fixed_compound(const Vec& pos, const std::vector<Part<T>>& parts, const Quat& q = unrotated) {
    return with_own_parts([&] { return add_fixed_compound(pos, add_compound_type(parts, T(1)), q); });
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

  // Appends any validated record (a compound's parts already in parts());
  // returns its index.
  std::size_t add(const Body<T>& b) {
    validate_body(b, bodies_.size(), parts_);
    require_material(b, bodies_.size());
    bodies_.push_back(b);
    return bodies_.size() - 1;
  }

  // Validates every record (after the user's engine changed them in place), or record i.
  void validate() const {
    for (std::size_t i = 0; i < bodies_.size(); ++i) validate(i);
  }
  void validate(std::size_t i) const {
    validate_body(bodies_[i], i, parts_);
    require_material(bodies_[i], i);
  }

  // A material (validated) for bodies to name by the id returned: 1, 2, ...;
  // id 0 is the world's default (ContactSettings::friction, ::restitution).
  // Two bodies' materials combine as combine_materials() says unless
  // set_material_pair() names the pair.
  std::uint32_t add_material(const Material<T>& m) { return materials_.add(m); }
  void set_material_pair(std::uint32_t a, std::uint32_t b, const Material<T>& m) { materials_.set_pair(a, b, m); }
  // Body i is of material id (an id add_material() returned, or 0).
  void set_material(std::size_t i, std::uint32_t id) {
    Body<T> b = bodies_.at(i);
    b.material = id;
    require_material(b, i);
    bodies_[i] = b;
  }
  const MaterialList<T>& materials() const { return materials_; }

  std::size_t size() const { return bodies_.size(); }
  Body<T>& operator[](std::size_t i) { return bodies_[i]; }
  const Body<T>& operator[](std::size_t i) const { return bodies_[i]; }
  std::vector<Body<T>>& records() { return bodies_; }
  const std::vector<Body<T>>& records() const { return bodies_; }
  // The parts of every compound type, in the order they were added,
  // positions relative to their type's centre of mass. Parts are never removed.
  const std::vector<Part<T>>& parts() const { return parts_; }

 private:
  void require_material(const Body<T>& b, std::size_t i) const {
    auto require = [&](std::uint32_t id, const std::string& field) {
      if (id >= materials_.size())
        throw InvalidBodyError(i, field, "names material " + std::to_string(id) + ", but the set has " +
                                             std::to_string(materials_.size()) + " (add_material)");
    };
    require(b.material, "material");
    if (b.shape == compound)
      for (std::size_t k = 0; k < std::size_t(b.shape_param[0]); ++k)
        require(parts_[b.first_part + k].material, "parts[" + std::to_string(k) + "].material");
  }
  void require_positive(T x, const char* field) const {
    if (!(x > 0) || !std::isfinite(x)) throw InvalidBodyError(bodies_.size(), field, "must be positive and finite");
  }
  // A moving body of the given principal inertia (body frame, diagonal).
  std::size_t add_moving(ShapeKind kind, const std::array<T, shape_param_rows>& param, const Vec& pos, const Quat& q,
                         T mass, const Vec& principal_inertia) {
    require_positive(mass, "mass");
    Body<T> b = fixed_record(kind, param, pos, q);
    b.status = active;
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
  Body<T> fixed_record(ShapeKind kind, const std::array<T, shape_param_rows>& param, const Vec& pos,
                       const Quat& q) const {
    Body<T> b;
    b.status = fixed;
    b.shape = kind;
    b.shape_param = param;
    b.pos = pos;
    b.q = q;
    return b;
  }
  std::size_t add_fixed(ShapeKind kind, const std::array<T, shape_param_rows>& param, const Vec& pos, const Quat& q) {
    return add(fixed_record(kind, param, pos, q));
  }

  // A compound has 1 to max_parts valid parts, named before any arithmetic.
  void require_parts(const std::vector<Part<T>>& parts) const {
    const std::size_t index = bodies_.size();
    if (parts.empty() || parts.size() > max_parts)
      throw InvalidBodyError(index, "parts", "a compound has 1 to 256 parts");
    for (std::size_t k = 0; k < parts.size(); ++k) validate_part(parts[k], k, index);
  }
  // Appends the parts, moved to the centre of mass, and returns the type that
  // names them (its bounds and feature size from them).
  CompoundType<T> store_type(const std::vector<Part<T>>& parts, T mass, const std::array<T, 9>& inertia,
                             const Vec& centre) {
    CompoundType<T> t;
    t.first_part = std::uint32_t(parts_.size());
    t.count = std::uint32_t(parts.size());
    t.mass = mass;
    t.inertia = inertia;
    const math::Matrix3x3<double> inv = math::inverse_spd(math::Matrix3x3<double>(
        inertia[0], inertia[1], inertia[2], inertia[3], inertia[4], inertia[5], inertia[6], inertia[7], inertia[8]));
    for (int k = 0; k < 9; ++k) t.inv_inertia[k] = T(inv[k]);
    t.centre = centre;
    t.feature = std::numeric_limits<T>::infinity();
    for (Part<T> part : parts) {
      for (int r = 0; r < 3; ++r) part.pos[r] -= centre[r];
      const auto& p = part.shape_param;
      const T reach = std::sqrt(part.pos[0] * part.pos[0] + part.pos[1] * part.pos[1] + part.pos[2] * part.pos[2]) +
                      shape_bound<T>(part.shape, p[0], p[1], p[2]);
      t.bound = std::max(t.bound, reach);
      t.feature = std::min(t.feature, shape_feature_size<T>(part.shape, p[0], p[1], p[2]));
      parts_.push_back(part);
    }
    return t;
  }
  // The fixed record of a body of the type whose frame origin lies at pos:
  // its centre of mass at pos + R(q) centre.
  Body<T> compound_record(const Vec& pos, const CompoundType<T>& type, const Quat& q) const {
    const math::Matrix3x3<T> R = math::to_rotation_matrix(math::Quaternion<T>(q[0], q[1], q[2], q[3]));
    Vec x = pos;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) x[r] += R(r, k) * type.centre[k];
    Body<T> b = fixed_record(compound, {T(type.count), type.bound, type.feature, 0}, x, q);
    b.first_part = type.first_part;
    return b;
  }
  // Adds a compound whose parts are its own: a rejected body leaves no parts behind.
  template <class F>
  std::size_t with_own_parts(F&& add_body) {
    const std::size_t mark = parts_.size();
    try {
      return add_body();
    } catch (...) {
      parts_.resize(mark);
      throw;
    }
  }

  std::vector<Part<T>> parts_;
  std::vector<Body<T>> bodies_;
  MaterialList<T> materials_;
};

}  // namespace gpusolve::rbd
