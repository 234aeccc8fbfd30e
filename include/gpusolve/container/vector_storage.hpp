// The storage shared by VectorD1/D2/D3: logical and padded extents over one
// Buffer, zero-initialised, with fill, resize and the information messages.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include "gpusolve/container/parameters.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/memory/buffer.hpp"
#include "gpusolve/policy/runtime.hpp"

#if __has_include(<cuda/std/mdspan>)
#include <cuda/std/mdspan>
#define GPUSOLVE_HAS_MDSPAN 1
#else
#define GPUSOLVE_HAS_MDSPAN 0
#endif

namespace gpusolve {

using extents3 = std::array<std::size_t, 3>;  // (x, y, z); unused dimensions are 1

namespace detail {

// Writes v to every logical element of a padded 3-D block; one index per element.
template <class T>
struct FillElements {
  T* ptr;
  std::size_t nx, ny, px, py;
  T value;
  GPUSOLVE_HD void operator()(std::size_t idx) const {
    const std::size_t i = idx % nx, r = idx / nx;
    const std::size_t j = r % ny, k = r / ny;
    ptr[(k * py + j) * px + i] = value;
  }
};

// Defined in gpusolve/container/copy.hpp (which needs this header's extents).
template <class Dst, class Src>
void copy_containers(Dst& dst, const Src& src, bool async, stream_t stream);

inline std::string shape_string(const extents3& e, std::size_t rank) {
  std::ostringstream os;
  for (std::size_t d = 0; d < rank; ++d) os << (d ? " x " : "") << e[d];
  return os.str();
}

// Largest power of two (up to 4096) that divides the address: what a report calls alignment.
inline std::size_t address_alignment(const void* p) {
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  std::size_t al = 1;
  while (al < 4096 && a % (al * 2) == 0) al *= 2;
  return al;
}

template <class T, std::size_t Rank, class Params>
class VectorStorage {
  static_assert(Rank >= 1 && Rank <= 3, "gpusolve: containers have 1 to 3 dimensions");

 public:
  using value_type = T;
  using params = Params;
  using device_type = typename Params::device_type;
  using allocator_type = typename Params::allocator_type;
  using layout_type = typename Params::layout_type;
  using compiletime_policy = typename Params::compiletime_policy;
  using runtime_policy = typename Params::runtime_policy;
  using memory_kind = typename Params::memory_kind;
  static constexpr std::size_t rank = Rank;
  static constexpr bool host_accessible = memory::is_host_accessible_v<memory_kind>;

  // Logical extents (what the user asked for).
  std::size_t size_x() const noexcept { return n_[0]; }
  std::size_t size_y() const noexcept { return n_[1]; }
  std::size_t size_z() const noexcept { return n_[2]; }
  const extents3& extents() const noexcept { return n_; }
  std::size_t size() const noexcept { return n_[0] * n_[1] * n_[2]; }
  bool empty() const noexcept { return size() == 0; }
  // Padded extents: pitch() is the distance in elements between rows (padded x).
  std::size_t pitch() const noexcept { return p_[0]; }
  std::size_t padded_y() const noexcept { return p_[1]; }
  std::size_t padded_z() const noexcept { return p_[2]; }
  const extents3& padded_extents() const noexcept { return p_; }
  std::size_t allocated() const noexcept { return buf_.size(); }  // elements, padding included

  T* data() noexcept { return buf_.data(); }
  const T* data() const noexcept { return buf_.data(); }

  // Makes this container the logical shape of `other` (any rank-equal container);
  // like resize, contents are lost and zero afterwards.
  template <class Other>
  void resize_as(const Other& other) {
    static_assert(Other::rank == Rank, "gpusolve: resize_as needs a container of the same rank");
    reshape(other.extents());
  }

  // Sets every logical element to v (padding stays zero). On device::gpu it runs
  // on `stream`, asynchronously: a kernel through gpusolve::launch (nvcc
  // translation units only) or cudaMemsetAsync when v is all zero bytes.
  void fill(const T& v, stream_t stream = stream_t{}) {
    if (empty()) return;
    if (std::is_same_v<device_type, device::gpu> && all_zero_bytes(v)) {
      buf_.zero(stream);
      return;
    }
    launch(device_type{}, size(), FillElements<T>{data(), n_[0], n_[1], p_[0], p_[1], v}, stream);
  }

#if GPUSOLVE_HAS_MDSPAN
  using mdspan_type = cuda::std::mdspan<T, cuda::std::dextents<std::size_t, Rank>, cuda::std::layout_stride>;
  using const_mdspan_type =
      cuda::std::mdspan<const T, cuda::std::dextents<std::size_t, Rank>, cuda::std::layout_stride>;
  // A libcu++ mdspan over the logical elements, strided by the padding; pass it
  // to kernels by value like view().
  mdspan_type mdspan() noexcept { return make_mdspan<T>(data()); }
  const_mdspan_type mdspan() const noexcept { return make_mdspan<const T>(data()); }
#endif

 protected:
  VectorStorage() = default;
  explicit VectorStorage(const extents3& n) { reshape(n); }
  // Deep copies; assigning a different logical shape throws (see copy()).
  VectorStorage(const VectorStorage& o) : VectorStorage(o.n_) { copy_containers(*this, o, false, stream_t{}); }
  VectorStorage& operator=(const VectorStorage& o) {
    copy_containers(*this, o, false, stream_t{});
    return *this;
  }
  // Moves take the allocation; the source is left empty.
  VectorStorage(VectorStorage&& o) noexcept
      : buf_(std::move(o.buf_)), n_(std::exchange(o.n_, no_extents)), p_(std::exchange(o.p_, no_extents)) {}
  VectorStorage& operator=(VectorStorage&& o) noexcept {
    buf_ = std::move(o.buf_);
    n_ = std::exchange(o.n_, no_extents);
    p_ = std::exchange(o.p_, no_extents);
    return *this;
  }
  ~VectorStorage() = default;

  // Reallocates for logical extents n; the contents are lost (all zero after).
  void reshape(const extents3& n) {
    extents3 p{};
    for (int d = 0; d < 3; ++d) {
      p[d] = d < int(Rank) ? layout_type::padded(n[d], d) : 1;
      if (p[d] < n[d])
        throw InvalidArgumentError("gpusolve: layout policy padded an extent below its logical size");
    }
    const bool any_empty = n[0] == 0 || n[1] == 0 || n[2] == 0;
    buf_ = memory::Buffer<T, allocator_type>();  // free first: peak memory is one allocation
    buf_ = memory::Buffer<T, allocator_type>(any_empty ? 0 : p[0] * p[1] * p[2]);
    n_ = n;
    p_ = p;
    runtime::report_info<runtime_policy>([&] { return describe_allocation(); });
  }

 private:
  static bool all_zero_bytes(const T& v) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (unsigned char b : bytes)
      if (b) return false;
    return true;
  }

  std::string describe_allocation() const {
    std::ostringstream os;
    os << "gpusolve: VectorD" << Rank << " on " << device_type::name << " (" << memory_kind::name
       << " memory): logical " << shape_string(n_, Rank) << ", padded " << shape_string(p_, Rank)
       << ", row pitch " << p_[0] * sizeof(T) << " bytes, " << buf_.bytes() << " bytes allocated";
    if (buf_.data()) os << ", base address aligned to " << address_alignment(buf_.data()) << " bytes";
    return os.str();
  }

#if GPUSOLVE_HAS_MDSPAN
  template <class U>
  cuda::std::mdspan<U, cuda::std::dextents<std::size_t, Rank>, cuda::std::layout_stride> make_mdspan(
      U* ptr) const noexcept {
    using E = cuda::std::dextents<std::size_t, Rank>;
    cuda::std::array<std::size_t, Rank> ext{}, stride{};
    std::size_t s = 1;
    for (std::size_t d = 0; d < Rank; ++d) {
      ext[d] = n_[d];
      stride[d] = s;
      s *= p_[d];
    }
    return {ptr, cuda::std::layout_stride::mapping<E>(E(ext), stride)};
  }
#endif

  // Unused dimensions stay 1 so that size() is the product of all three.
  static constexpr extents3 no_extents{0, Rank > 1 ? 0 : 1, Rank > 2 ? 0 : 1};

  memory::Buffer<T, allocator_type> buf_;
  extents3 n_ = no_extents;
  extents3 p_ = no_extents;
};

}  // namespace detail
}  // namespace gpusolve
