// Element storage and expression plumbing shared by the value types Vector3,
// Matrix3x3 and Quaternion: objects that hold their elements (in registers).
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/expr.hpp"

namespace gpusolve::math::detail {

template <class Derived, class Kind, class T>
class Value : public Expr<Derived, Kind, T> {
 public:
  static constexpr bool needs_temporary = false;

  Value() = default;
  // A new object aliases nothing, so it is filled straight from the expression.
  template <class E>
  GPUSOLVE_HD Value(const Expr<E, Kind, T>& e) {
    copy_elements(*this, e.derived());
  }
  template <class E>
  GPUSOLVE_HD Derived& operator=(const Expr<E, Kind, T>& e) {
    assign(*this, e.derived());
    return this->derived();
  }

  GPUSOLVE_HD T operator[](std::size_t i) const { return v_[i]; }
  GPUSOLVE_HD T& operator[](std::size_t i) { return v_[i]; }

 protected:
  GPUSOLVE_HD explicit Value(const T (&v)[Kind::size]) {
    for (std::size_t i = 0; i < Kind::size; ++i) v_[i] = v[i];
  }

 private:
  T v_[Kind::size] = {};
};

}  // namespace gpusolve::math::detail
