// Parts: the primitives compound bodies are made of (pe's Union, thesis 3.1),
// each at a pose of its own in its body's frame.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/container/vector_d2.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/rbd/bodies/shapes.hpp"

namespace gpusolve::rbd {

// One part as a user gives it: a sphere, box or capsule (shape parameters as
// in shapes.hpp), its centre and orientation (w, x, y, z) in the compound's frame.
template <class T = float>
struct Part {
  ShapeKind shape = sphere;
  std::array<T, shape_param_rows> shape_param{};
  std::array<T, 3> pos{};
  std::array<T, 4> q{1, 0, 0, 0};
  std::uint32_t material = 0;  // an id of the BodySet's materials(); 0: the body's own
};

// The parts of every compound on one backend, structure of arrays like
// Bodies: a compound body's parts are the rows [first_part, first_part + count).
// Positions are relative to the body's centre of mass, rotations row-major
// (part -> body frame).
template <class Device, class T = float>
struct Parts {
  template <class E>
  using D1 = VectorD1<E, device_is<Device>>;
  using VecD2 = VectorD2<T, device_is<Device>>;

  D1<std::uint8_t> shape;  // ShapeKind
  VecD2 shape_param;       // n x 4
  VecD2 pos;               // n x 3
  VecD2 R;                 // n x 9
  D1<std::uint32_t> material;  // 0: the body's own

  std::size_t size() const { return shape.size(); }
  // Reallocates for n parts (contents lost).
  void resize(std::size_t n) {
    shape.resize(n);
    shape_param.resize(n, shape_param_rows);
    pos.resize(n, 3);
    R.resize(n, 9);
    material.resize(n);
  }
  template <class D2>
  Parts& operator=(const Parts<D2, T>& o) {
    if (size() != o.size()) resize(o.size());
    shape = o.shape;
    shape_param = o.shape_param;
    pos = o.pos;
    R = o.R;
    material = o.material;
    return *this;
  }

  struct View {
    decltype(std::declval<D1<std::uint8_t>&>().view()) shape;
    decltype(std::declval<VecD2&>().view()) shape_param, pos, R;
    decltype(std::declval<D1<std::uint32_t>&>().view()) material;
  };
  View view() { return {shape.view(), shape_param.view(), pos.view(), R.view(), material.view()}; }
};

}  // namespace gpusolve::rbd
