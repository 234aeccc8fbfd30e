// ConstantDeviceMemory: a container's descriptor (its view) held in __constant__
// memory, written from the host by assignment and read in kernels (nvcc only).
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

#if GPUSOLVE_HAS_NVCC
namespace gpusolve::memory {
namespace detail {

// A container stores its view; a view (or any trivially copyable struct) stores itself.
template <class C, class = void>
struct descriptor_of {
  using type = C;
};
template <class C>
struct descriptor_of<C, std::void_t<typename C::view_type>> {
  using type = typename C::view_type;
};

// One __constant__ slot per (descriptor, tag) pair. nvcc accepts only constant
// initialisation here: a descriptor type whose members are either all
// default-initialised in class or none of them (trivial) works; one that mixes
// the two fails to compile with "dynamic initialization is not supported".
template <class V, class Tag>
__constant__ V constant_slot;

}  // namespace detail

// Usage (thesis Listing 1, line 16):
//   namespace { struct c_tag; }  // a tag private to this translation unit
//   memory::ConstantDeviceMemory<VectorD1<unsigned, device::gpu>, c_tag> cConst;
//   cConst = c;                  // copies c.view() into constant memory
//   launch(device::gpu{}, n, Kernel{cConst, ...});  // kernel reads cConst.get()
// The handle is an empty, trivially copyable object: pass it to kernels by value.
// Without relocatable device code each translation unit has its own constant
// memory, so the tag must not be shared between translation units: declare it
// in an anonymous namespace and write and read the slot from the same file.
template <class Content, class Tag>
class ConstantDeviceMemory {
 public:
  using value_type = typename detail::descriptor_of<Content>::type;
  static_assert(std::is_trivially_copyable_v<value_type>,
                "gpusolve: constant memory holds trivially copyable descriptors only");
  static_assert(sizeof(value_type) <= 64 * 1024, "gpusolve: constant memory holds at most 64 KiB");

  // Writes the descriptor; returns once it is in constant memory.
  ConstantDeviceMemory& operator=(const value_type& v) {
    GPUSOLVE_CUDA_CHECK(cudaMemcpyToSymbol(detail::constant_slot<value_type, Tag>, &v, sizeof(value_type)));
    return *this;
  }
  // Writes the view of a container (`cConst = c;`).
  template <class C, class = std::enable_if_t<std::is_convertible_v<decltype(std::declval<C&>().view()), value_type>>>
  ConstantDeviceMemory& operator=(C& container) {
    return *this = value_type(container.view());
  }

  // Queues the write on `stream`; v may go out of scope on return (the runtime
  // stages pageable sources before cudaMemcpyToSymbolAsync returns).
  void assign_async(const value_type& v, stream_t stream) {
    GPUSOLVE_CUDA_CHECK(cudaMemcpyToSymbolAsync(detail::constant_slot<value_type, Tag>, &v, sizeof(value_type),
                                                0, cudaMemcpyHostToDevice, stream));
  }
  template <class C, class = std::enable_if_t<std::is_convertible_v<decltype(std::declval<C&>().view()), value_type>>>
  void assign_async(C& container, stream_t stream) {
    assign_async(value_type(container.view()), stream);
  }

  // Reads the descriptor back to the host.
  value_type read() const {
    value_type v;
    GPUSOLVE_CUDA_CHECK(cudaMemcpyFromSymbol(&v, detail::constant_slot<value_type, Tag>, sizeof(value_type)));
    return v;
  }

  // The descriptor, in device code: loads go through the constant cache.
  __device__ static const value_type& get() { return detail::constant_slot<value_type, Tag>; }
};

}  // namespace gpusolve::memory
#endif
