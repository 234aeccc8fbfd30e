// Materials: a friction coefficient, a coefficient of restitution and
// rolling and spinning resistance per material id, the pair of two bodies'
// materials combined by a rule or set per pair, and the table a detection
// reads once per contact.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/device.hpp"

namespace gpusolve::rbd {

template <class T = float>
struct Material {
  T friction = T(0.5);  // Coulomb coefficient, >= 0
  T restitution = T(0);  // normal separation speed over approach speed, in [0, 1]
  // Resistance to rolling and to spinning about the normal, as lengths (m): the
  // contact resists with a torque of up to rolling N and spinning N (Chrono's
  // rolling and spinning friction). Only a World of a contact model with
  // angular rows (ConeRollingFriction) has them; others refuse a nonzero value.
  T rolling = T(0);
  T spinning = T(0);
};

// Throws InvalidArgumentError naming the material and its field.
template <class T>
void validate_material(const Material<T>& m, std::size_t id) {
  auto bad = [&](const char* field, const char* why) {
    std::ostringstream os;
    os << "gpusolve: material " << id << ", field `" << field << "`: " << why;
    throw InvalidArgumentError(os.str());
  };
  if (!(m.friction >= 0) || !std::isfinite(m.friction)) bad("friction", "must be non-negative and finite");
  if (!(m.restitution >= 0 && m.restitution <= 1)) bad("restitution", "must lie in [0, 1]");
  if (!(m.rolling >= 0) || !std::isfinite(m.rolling)) bad("rolling", "must be non-negative and finite (a length)");
  if (!(m.spinning >= 0) || !std::isfinite(m.spinning)) bad("spinning", "must be non-negative and finite (a length)");
}

// The pair of two materials where no pair entry says otherwise: the geometric
// mean of the friction coefficients and the larger restitution (the rules of
// PhysX's defaults for friction "multiply"/"average" aside, Box2D v3's
// b2MixFriction and b2MixRestitution), and the larger rolling and spinning
// resistance (Box2D v3 takes the larger rolling resistance of two shapes: the
// softer body's deformation resists). A material with itself is itself.
template <class T>
GPUSOLVE_HD Material<T> combine_materials(const Material<T>& a, const Material<T>& b) {
  return {a.friction == b.friction ? a.friction : T(std::sqrt(a.friction * b.friction)),
          a.restitution > b.restitution ? a.restitution : b.restitution, a.rolling > b.rolling ? a.rolling : b.rolling,
          a.spinning > b.spinning ? a.spinning : b.spinning};
}

// The host's list: material 0 is the world's default, whose friction,
// restitution, rolling and spinning come from the solver settings
// (ContactSettings::friction, ::restitution, ::rolling, ::spinning) at every
// step; add() gives ids 1, 2, ... Pair entries between two added materials
// override the combination.
template <class T = float>
class MaterialList {
 public:
  MaterialList() : list_(1) {}

  std::uint32_t add(const Material<T>& m) {
    validate_material(m, list_.size());
    list_.push_back(m);
    changed();
    return std::uint32_t(list_.size() - 1);
  }
  // The pair (a, b) and (b, a) of two added materials behaves as m.
  void set_pair(std::uint32_t a, std::uint32_t b, const Material<T>& m) {
    for (std::uint32_t id : {a, b})
      if (id == 0 || id >= list_.size()) {
        std::ostringstream os;
        os << "gpusolve: material pair (" << a << ", " << b << "): material " << id
           << (id == 0 ? " is the world's default, which combines with every other"
                       : " was not added");
        throw InvalidArgumentError(os.str());
      }
    validate_material(m, a);
    entries_.push_back({a, b, m});
    changed();
  }

  std::size_t size() const { return list_.size(); }
  const Material<T>& operator[](std::size_t id) const { return list_[id]; }
  // Changes with every add() and set_pair(): a copy on a device is stale when it differs.
  std::size_t version() const { return version_; }

  // The dense table of the added materials' pairs, row a, column b (row and
  // column 0 unused: the default's pairs combine at each contact).
  const std::vector<Material<T>>& pairs() const {
    if (pairs_.empty()) {
      const std::size_t m = list_.size();
      pairs_.resize(m * m);
      for (std::size_t a = 0; a < m; ++a)
        for (std::size_t b = 0; b < m; ++b) pairs_[a * m + b] = combine_materials(list_[a], list_[b]);
      for (const Entry& e : entries_) pairs_[e.a * m + e.b] = pairs_[e.b * m + e.a] = e.m;
    }
    return pairs_;
  }

 private:
  void changed() {
    pairs_.clear();  // rebuilt from the list and the entries when next asked for
    ++version_;
  }
  struct Entry {
    std::uint32_t a, b;
    Material<T> m;
  };
  std::vector<Material<T>> list_;
  std::vector<Entry> entries_;
  mutable std::vector<Material<T>> pairs_;
  std::size_t version_ = 0;
};

// Throws InvalidArgumentError naming the first material, or pair entry, with a
// rolling or spinning resistance, and `why` (a World whose contact model has
// no angular rows would ignore it).
template <class T>
void refuse_angular_resistance(const MaterialList<T>& list, const char* why) {
  const std::size_t m = list.size();
  for (std::size_t a = 1; a < m; ++a)
    for (std::size_t b = a; b < m; ++b) {
      const Material<T>& pair = list.pairs()[a * m + b];
      if (pair.rolling == T(0) && pair.spinning == T(0)) continue;
      std::ostringstream os;
      os << "gpusolve: material ";
      if (a == b)
        os << a;
      else
        os << "pair (" << a << ", " << b << ")";
      os << ", field `" << (pair.rolling != T(0) ? "rolling" : "spinning") << "`: " << why;
      throw InvalidArgumentError(os.str());
    }
}

// What a detection needs besides the table to give its contacts their
// materials: the world's default material (id 0), the restitution threshold
// and the step's length (a contact bounces only for an impact within the
// step). A friction coefficient alone converts to it (no restitution).
template <class T = float>
struct ContactDefaults {
  Material<T> world{};
  T bounce_threshold = T(1);  // m/s
  T dt = T(0);
  ContactDefaults() = default;
  ContactDefaults(T friction) : world{friction, T(0)} {}  // NOLINT: a friction coefficient is a ContactDefaults
  ContactDefaults(const Material<T>& m, T threshold, T step) : world(m), bounce_threshold(threshold), dt(step) {}
};

// The pair table on a backend, and what a contact reads of it.
template <class Device, class T = float>
struct MaterialPairs {
  VectorD1<T, device_is<Device>> friction, restitution, rolling, spinning;  // m x m, row-major
  std::size_t count = 0;                                  // m
  std::size_t version = ~std::size_t(0);                  // the MaterialList's it holds

  struct View {
    const T *friction, *restitution, *rolling, *spinning;
    std::uint32_t count;
    std::uint32_t unused = 0;  // no indeterminate bytes: a detection's graph key compares views byte by byte
    // The pair of materials a and b, with the world's default material d.
    // (A caller that does not use rolling or spinning does not load them.)
    GPUSOLVE_HD Material<T> pair(std::uint32_t a, std::uint32_t b, const Material<T>& d) const {
      if (a == 0 && b == 0) return d;
      if (a == 0 || b == 0) {
        const std::uint32_t k = a == 0 ? b : a;
        return combine_materials(d, at(k * count + k));
      }
      return at(a * count + b);
    }
    GPUSOLVE_HD Material<T> at(std::size_t k) const { return {friction[k], restitution[k], rolling[k], spinning[k]}; }
  };

  template <class D2>
  MaterialPairs& operator=(const MaterialPairs<D2, T>& o) {
    for (auto [to, from] : {std::pair{&friction, &o.friction}, std::pair{&restitution, &o.restitution},
                            std::pair{&rolling, &o.rolling}, std::pair{&spinning, &o.spinning}}) {
      to->resize(from->size());
      *to = *from;
    }
    count = o.count;
    version = o.version;
    return *this;
  }

  // Copies the list's pair table, unless this holds its version already.
  void copy_from(const MaterialList<T>& list) {
    if (list.version() == version) return;
    const auto& pairs = list.pairs();
    VectorD1<T, device_is<device::cpu>> f(pairs.size()), e(pairs.size()), r(pairs.size()), s(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k)
      f(k) = pairs[k].friction, e(k) = pairs[k].restitution, r(k) = pairs[k].rolling, s(k) = pairs[k].spinning;
    for (auto [to, from] : {std::pair{&friction, &f}, std::pair{&restitution, &e}, std::pair{&rolling, &r},
                            std::pair{&spinning, &s}}) {
      to->resize(from->size());
      *to = *from;
    }
    count = list.size();
    version = list.version();
  }
  View view() {
    return {friction.data(), restitution.data(), rolling.data(), spinning.data(), std::uint32_t(count)};
  }
};

}  // namespace gpusolve::rbd
