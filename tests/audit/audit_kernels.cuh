// The kernels of the SASS audit (thesis 4.2.2): the vector triad and the
// contact-point expression of Eq. (9) in plain C++, expression templates on
// Global types and (Eq. 9) the cached mix, plus ways of handing a kernel its
// container descriptors. Shared by the audited cubin and the GPU test.
#pragma once

#include <cstddef>

#include "gpusolve/container/vector_d2_offset.hpp"
#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/memory/constant_device_memory.hpp"

namespace gpusolve_audit {

template <class T> using D2 = gpusolve::VectorD2View<T>;
template <class T> using D1 = gpusolve::VectorD1View<T>;
using Offset3 = gpusolve::VectorD2Offset<3>;

// The baseline of the thesis's "plain C++" rows: a 3-vector whose operators
// return new vectors, as in code written without expression templates.
namespace plain {

template <class T>
struct Vec3 {
  T v[3];
};

template <class T>
GPUSOLVE_HD Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) {
  return {{a.v[0] + b.v[0], a.v[1] + b.v[1], a.v[2] + b.v[2]}};
}
template <class T>
GPUSOLVE_HD Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) {
  return {{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]}};
}
template <class T>
GPUSOLVE_HD Vec3<T> operator*(T s, const Vec3<T>& a) {
  return {{s * a.v[0], s * a.v[1], s * a.v[2]}};
}
template <class T>
GPUSOLVE_HD Vec3<T> operator*(const Vec3<T>& a, T s) {
  return s * a;
}
template <class T>
GPUSOLVE_HD Vec3<T> operator%(const Vec3<T>& a, const Vec3<T>& b) {
  return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2],
           a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}

// Row k of a width-3 VectorD2 at column i, as thesis Listing 7 reads and writes it.
template <class T>
GPUSOLVE_HD Vec3<T> load(const D2<T>& m, std::size_t i) {
  Vec3<T> r;
  for (std::size_t k = 0; k < 3; ++k) r.v[k] = m(i, k);
  return r;
}
template <class T>
GPUSOLVE_HD void store(const D2<T>& m, std::size_t i, const Vec3<T>& x) {
  for (std::size_t k = 0; k < 3; ++k) m(i, k) = x.v[k];
}

}  // namespace plain

// Vector triad a = b + c * d: a, b, d are 3 x n VectorD2s, c a VectorD1 with
// one factor per thread (thesis Listings 6 to 8). The offsets are built from
// the common pitch of a, b and d.
template <class T>
struct TriadArgs {
  D2<T> a, b, d;
  D1<T> c;
  Offset3 offset;
  GPUSOLVE_HD std::size_t size() const { return a.size_x(); }
};

template <class T>
struct TriadPlain : TriadArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const plain::Vec3<T> b = plain::load(this->b, i), d = plain::load(this->d, i);
    plain::store(this->a, i, b + this->c[i] * d);
  }
};

template <class T>
struct TriadET : TriadArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    using G = gpusolve::math::Vector3Global<T>;
    G a(this->a, this->offset, i);
    const G b(this->b, this->offset, i), d(this->d, this->offset, i);
    a = b + this->c[i] * d;
  }
};

// Eq. (9), Fig. 10: the contact point's expected position
// p = q + v dt + r - (r x w) dt, with q the body position, v its velocity, r the
// contact point relative to the body, w its angular velocity; dt is a kernel
// parameter shared by all threads.
template <class T>
struct ContactArgs {
  D2<T> p, q, v, r, w;
  Offset3 offset;
  T dt = 0;  // initialised, so the struct may live in __constant__ memory
  GPUSOLVE_HD std::size_t size() const { return p.size_x(); }
  // Element i of one of the vectors as a Vector3Global.
  GPUSOLVE_HD gpusolve::math::Vector3Global<T> at(const D2<T>& m, std::size_t i) const {
    return {m, offset, i};
  }
};

template <class T>
struct ContactPlain : ContactArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    const plain::Vec3<T> q = plain::load(this->q, i), v = plain::load(this->v, i),
                         r = plain::load(this->r, i), w = plain::load(this->w, i);
    const T dt = this->dt;
    plain::store(this->p, i, q + v * dt + r - (r % w) * dt);
  }
};

// Every operand a Vector3Global (thesis Table 5, "ET"), assigned with the
// library's assign(): the cross product makes it evaluate into a temporary.
template <class T>
struct ContactET : ContactArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    auto p = this->at(this->p, i);
    const auto q = this->at(this->q, i), v = this->at(this->v, i), r = this->at(this->r, i),
               w = this->at(this->w, i);
    const T dt = this->dt;
    p = q + v * dt + r - (r % w) * dt;
  }
};

// The same expression written element by element straight into p, as the
// thesis's assignment did: each store may alias the operands read after it.
// Safe here only because p is none of q, v, r, w.
template <class T>
struct ContactETWriteThrough : ContactArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    auto p = this->at(this->p, i);
    const auto q = this->at(this->q, i), v = this->at(this->v, i), r = this->at(this->r, i),
               w = this->at(this->w, i);
    const T dt = this->dt;
    // Every leaf is a named Global held by copy, so the expression outlives no operand.
    const auto e = q + v * dt + r - (r % w) * dt;
    for (std::size_t k = 0; k < 3; ++k) p[k] = e[k];
  }
};

// r and w, each read twice by the expression, copied into Vector3 values; q, v
// and p stay Global (thesis Table 5, "ET (cached)").
template <class T>
struct ContactCached : ContactArgs<T> {
  GPUSOLVE_HD void operator()(std::size_t i) const {
    auto p = this->at(this->p, i);
    const auto q = this->at(this->q, i), v = this->at(this->v, i);
    const gpusolve::math::Vector3<T> r(this->at(this->r, i)), w(this->at(this->w, i));
    const T dt = this->dt;
    p = q + v * dt + r - (r % w) * dt;
  }
};

#if GPUSOLVE_HAS_NVCC
// One element per thread, out-of-range threads return: the thesis's kernel
// shape (Listing 6), so static counts are those of one body. The body, with its
// descriptors, is an ordinary by-value kernel parameter.
template <class Body>
__global__ void each_element(Body body) {
  const std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= body.size()) return;
  body(i);
}

// The same, the parameter declared __grid_constant__: the body is read in
// place in the parameter bank and may be referenced without a local copy.
template <class Body>
__global__ void each_element_grid_constant(const __grid_constant__ Body body) {
  const std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= body.size()) return;
  body(i);
}

// The body (all descriptors) held in __constant__ memory through
// ConstantDeviceMemory, as in thesis Listing 6; the kernel parameter is empty.
template <class Body, class Tag>
struct FromConstant {
  using Memory = gpusolve::memory::ConstantDeviceMemory<Body, Tag>;
  __device__ std::size_t size() const { return Memory::get().size(); }
  __device__ void operator()(std::size_t i) const { Memory::get()(i); }
};

// Private to each translation unit, as ConstantDeviceMemory requires.
namespace {
struct ConstantTag;
}  // namespace

template <class Body>
using InConstant = FromConstant<Body, ConstantTag>;

// How a launch hands the kernel its body: the three rows of the audit's
// descriptor comparison.
enum class Pass { by_value, grid_constant, constant_memory };

constexpr unsigned block = 128;
inline unsigned blocks_for(std::size_t n) { return static_cast<unsigned>((n + block - 1) / block); }

// Runs body over [0, body.size()) one element per thread, asynchronously.
template <class Body>
void launch_each_element(const Body& body, Pass pass) {
  const unsigned blocks = blocks_for(body.size());
  switch (pass) {
    case Pass::by_value:
      each_element<<<blocks, block>>>(body);
      break;
    case Pass::grid_constant:
      each_element_grid_constant<<<blocks, block>>>(body);
      break;
    case Pass::constant_memory: {
      gpusolve::memory::ConstantDeviceMemory<Body, ConstantTag> slot;
      slot = body;  // synchronous: the kernel below sees it
      each_element<<<blocks, block>>>(InConstant<Body>{});
      break;
    }
  }
  GPUSOLVE_CUDA_CHECK(cudaGetLastError());
}
#endif

}  // namespace gpusolve_audit
