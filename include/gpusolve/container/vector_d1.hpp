// VectorD1: an owning 1-D container on the host or the GPU, configured by named parameters.
#pragma once

#include <cstddef>

#include "gpusolve/container/copy.hpp"
#include "gpusolve/container/parameters.hpp"
#include "gpusolve/container/vector_storage.hpp"
#include "gpusolve/container/vector_view.hpp"

#if GPUSOLVE_HAS_NVCC
#include <thrust/device_ptr.h>
#endif

namespace gpusolve {

// VectorD1<T, params...>: params in any order (see parameters.hpp). Contents are
// zero after construction and after resize. Assigning another VectorD1 of the
// same element type copies across memories (see copy()).
template <class T, class... Params>
class VectorD1 : public detail::VectorStorage<T, 1, ContainerParams<Params...>> {
  using Base = detail::VectorStorage<T, 1, ContainerParams<Params...>>;

 public:
  using typename Base::compiletime_policy;
  using view_type = VectorD1View<T, compiletime_policy>;
  using const_view_type = VectorD1View<const T, compiletime_policy>;

  VectorD1() = default;
  explicit VectorD1(std::size_t n) : Base(extents3{n, 1, 1}) {}
  template <class... Qs>
  explicit VectorD1(const VectorD1<T, Qs...>& o) {
    copy(*this, o);
  }
  template <class... Qs>
  VectorD1& operator=(const VectorD1<T, Qs...>& o) {
    copy(*this, o);
    return *this;
  }

  // Reallocates for n elements; the old contents are lost (zero after).
  void resize(std::size_t n) { this->reshape(extents3{n, 1, 1}); }

  view_type view() noexcept { return {this->data(), this->size_x()}; }
  const_view_type view() const noexcept { return {this->data(), this->size_x()}; }

  // Host element access, bounds-checked under compiletime::DebugPolicy.
  T& operator()(std::size_t i) { return host_view()(i); }
  const T& operator()(std::size_t i) const { return host_view()(i); }
  T& operator[](std::size_t i) { return host_view()(i); }
  const T& operator[](std::size_t i) const { return host_view()(i); }

  // Iterators for the standard algorithms (cpu) and Thrust: raw pointers on the
  // host, thrust::device_ptr on the GPU (nvcc translation units only).
  auto begin() noexcept { return iter(this->data()); }
  auto end() noexcept { return iter(this->data() + this->size_x()); }
  auto begin() const noexcept { return iter(this->data()); }
  auto end() const noexcept { return iter(this->data() + this->size_x()); }

 private:
  auto host_view() const {
    static_assert(Base::host_accessible,
                  "gpusolve: host element access needs a container in host memory; copy it to one first");
    return VectorD1View<T, compiletime_policy>{const_cast<T*>(this->data()), this->size_x()};
  }
  template <class P>
  static auto iter(P* p) noexcept {
    if constexpr (Base::host_accessible) {
      return p;
    } else {
#if GPUSOLVE_HAS_NVCC
      return thrust::device_ptr<P>(p);
#else
      static_assert(sizeof(P) == 0, "gpusolve: iterators over device memory are thrust::device_ptr and need nvcc");
#endif
    }
  }
};

}  // namespace gpusolve
