// VectorD3: an owning 3-D container (x contiguous, then y, then z, each padded)
// on the host or the GPU, configured by named parameters.
#pragma once

#include <cstddef>

#include "gpusolve/container/copy.hpp"
#include "gpusolve/container/parameters.hpp"
#include "gpusolve/container/vector_storage.hpp"
#include "gpusolve/container/vector_view.hpp"

namespace gpusolve {

// VectorD3<T, params...>: as VectorD2 with a third dimension; element (i, j, k)
// lives at data()[(k * padded_y() + j) * pitch() + i].
template <class T, class... Params>
class VectorD3 : public detail::VectorStorage<T, 3, ContainerParams<Params...>> {
  using Base = detail::VectorStorage<T, 3, ContainerParams<Params...>>;

 public:
  using typename Base::compiletime_policy;
  using view_type = VectorD3View<T, compiletime_policy>;
  using const_view_type = VectorD3View<const T, compiletime_policy>;

  VectorD3() = default;
  VectorD3(std::size_t nx, std::size_t ny, std::size_t nz) : Base(extents3{nx, ny, nz}) {}
  template <class... Qs>
  explicit VectorD3(const VectorD3<T, Qs...>& o) {
    copy(*this, o);
  }
  template <class... Qs>
  VectorD3& operator=(const VectorD3<T, Qs...>& o) {
    copy(*this, o);
    return *this;
  }

  // Reallocates for nx x ny x nz elements; the old contents are lost (zero after).
  void resize(std::size_t nx, std::size_t ny, std::size_t nz) { this->reshape(extents3{nx, ny, nz}); }

  view_type view() noexcept { return make_view<T>(); }
  const_view_type view() const noexcept { return make_view<const T>(); }

  // Host element access, bounds-checked under compiletime::DebugPolicy.
  T& operator()(std::size_t i, std::size_t j, std::size_t k) { return host_view()(i, j, k); }
  const T& operator()(std::size_t i, std::size_t j, std::size_t k) const { return host_view()(i, j, k); }

 private:
  template <class U>
  VectorD3View<U, compiletime_policy> make_view() const noexcept {
    return {const_cast<T*>(this->data()), this->size_x(), this->size_y(), this->size_z(), this->pitch(),
            this->padded_y()};
  }
  view_type host_view() const {
    static_assert(Base::host_accessible,
                  "gpusolve: host element access needs a container in host memory; copy it to one first");
    return make_view<T>();
  }
};

}  // namespace gpusolve
