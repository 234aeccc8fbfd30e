// Vector3Global, Matrix3x3Global, QuaternionGlobal: one element (index) of a
// structure-of-arrays VectorD2 of width 3, 9 or 4, read and written in place
// (thesis Listing 4).
#pragma once

#include <cstddef>

#include "gpusolve/container/bounds.hpp"
#include "gpusolve/container/vector_d2_offset.hpp"
#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/policy/compiletime.hpp"

namespace gpusolve::math {

// Element k of the object is entry (index, k) of the VectorD2, reached through
// the precomputed row offsets. Nothing is cached: every read and every write
// goes to memory, so an expression touches only the elements it needs, one at
// a time. For a value read several times, copy it into a Vector3 (Table 5's
// "cached" variant).
//
// Copying a Global copies the handle; assigning to one writes values, like
// assigning to the element it stands for.
template <class Kind, class T, class Check = compiletime::ReleasePolicy>
class Global : public Expr<Global<Kind, T, Check>, Kind, T> {
 public:
  using View = VectorD2View<T, Check>;
  using Offset = VectorD2Offset<Kind::size>;
  static constexpr bool needs_temporary = false;

  // `offset` must be built from this view's pitch (Offset::of(view)). It is held
  // by reference, as in the thesis: it is shared by all threads, often from
  // constant memory.
  GPUSOLVE_HD Global(const View& view, const Offset& offset, std::size_t index)
      : view_(view), offset_(offset), index_(index) {
    if constexpr (Check::bounds_check) {
      if (index >= view.nx || view.ny < Kind::size)
        gpusolve::detail::bounds_violation(2, index, Kind::size - 1, 0, view.nx, view.ny, 0);
    }
  }
  Global(const View&, const Offset&&, std::size_t) = delete;  // it would dangle
  Global(const Global&) = default;

  GPUSOLVE_HD Global& operator=(const Global& g) {
    assign(*this, g);
    return *this;
  }
  template <class E>
  GPUSOLVE_HD Global& operator=(const Expr<E, Kind, T>& e) {
    assign(*this, e.derived());
    return *this;
  }

  // A reference into the container, even on a const Global (a view's semantics).
  GPUSOLVE_HD T& operator[](std::size_t k) const { return view_(offset_(index_, k)); }

 private:
  View view_;
  const Offset& offset_;
  std::size_t index_;
};

template <class T, class Check = compiletime::ReleasePolicy>
using Vector3Global = Global<VectorKind, T, Check>;
template <class T, class Check = compiletime::ReleasePolicy>
using Matrix3x3Global = Global<MatrixKind, T, Check>;
template <class T, class Check = compiletime::ReleasePolicy>
using QuaternionGlobal = Global<QuaternionKind, T, Check>;

}  // namespace gpusolve::math
