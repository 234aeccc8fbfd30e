// VectorD2: an owning 2-D container (x contiguous, rows padded to the pitch)
// on the host or the GPU, configured by named parameters.
#pragma once

#include <cstddef>

#include "gpusolve/container/copy.hpp"
#include "gpusolve/container/parameters.hpp"
#include "gpusolve/container/vector_storage.hpp"
#include "gpusolve/container/vector_view.hpp"

namespace gpusolve {

// VectorD2<T, params...>: params in any order (see parameters.hpp); element
// (i, j) lives at data()[j * pitch() + i]. Contents are zero after construction
// and after resize. Assigning another VectorD2 of the same element type copies
// across memories and layouts (see copy()).
template <class T, class... Params>
class VectorD2 : public detail::VectorStorage<T, 2, ContainerParams<Params...>> {
  using Base = detail::VectorStorage<T, 2, ContainerParams<Params...>>;

 public:
  using typename Base::compiletime_policy;
  using view_type = VectorD2View<T, compiletime_policy>;
  using const_view_type = VectorD2View<const T, compiletime_policy>;

  VectorD2() = default;
  VectorD2(std::size_t nx, std::size_t ny) : Base(extents3{nx, ny, 1}) {}
  template <class... Qs>
  explicit VectorD2(const VectorD2<T, Qs...>& o) {
    copy(*this, o);
  }
  template <class... Qs>
  VectorD2& operator=(const VectorD2<T, Qs...>& o) {
    copy(*this, o);
    return *this;
  }

  // Reallocates for nx x ny elements; the old contents are lost (zero after).
  void resize(std::size_t nx, std::size_t ny) { this->reshape(extents3{nx, ny, 1}); }

  view_type view() noexcept { return {this->data(), this->size_x(), this->size_y(), this->pitch()}; }
  const_view_type view() const noexcept { return {this->data(), this->size_x(), this->size_y(), this->pitch()}; }

  // Host element access, bounds-checked under compiletime::DebugPolicy.
  T& operator()(std::size_t i, std::size_t j) { return host_view()(i, j); }
  const T& operator()(std::size_t i, std::size_t j) const { return host_view()(i, j); }

 private:
  view_type host_view() const {
    static_assert(Base::host_accessible,
                  "gpusolve: host element access needs a container in host memory; copy it to one first");
    return {const_cast<T*>(this->data()), this->size_x(), this->size_y(), this->pitch()};
  }
};

}  // namespace gpusolve
