// The allocator concept and the memory-kind tags that say where an allocator's bytes live.
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <type_traits>

#include "gpusolve/memory/allocation_label.hpp"

namespace gpusolve::memory {

// Where an allocation lives; copies pick their direction from these tags.
struct host {      // pageable host memory: readable by the CPU, staged by the driver for DMA
  static constexpr const char* name = "host";
};
struct pinned {    // page-locked host memory: readable by the CPU and by DMA directly
  static constexpr const char* name = "pinned";
};
struct device {    // GPU global memory: only kernels and CUDA copies reach it
  static constexpr const char* name = "device";
};

template <class M>
inline constexpr bool is_host_accessible_v = std::is_same_v<M, host> || std::is_same_v<M, pinned>;

// The allocator concept. A user allocator is any class with
//   using memory = memory::host | memory::pinned | memory::device;
//   static void* allocate(std::size_t bytes);          // throws OutOfMemoryError (or NoDeviceError)
//   static void  deallocate(void* p, std::size_t bytes) noexcept;
// allocate(0) may return nullptr. Rows of padded containers start aligned only
// as far as the returned base pointer is, so return at least 128-byte alignment.
template <class A, class = void>
struct is_allocator : std::false_type {};
template <class A>
struct is_allocator<A, std::void_t<typename A::memory,
                                   decltype(A::allocate(std::size_t{})),
                                   decltype(A::deallocate(nullptr, std::size_t{}))>>
    : std::bool_constant<std::is_same_v<typename A::memory, host> ||
                         std::is_same_v<typename A::memory, pinned> ||
                         std::is_same_v<typename A::memory, device>> {};
template <class A>
inline constexpr bool is_allocator_v = is_allocator<A>::value;

// Base-pointer alignment the library's allocators guarantee (cudaMalloc gives 256).
inline constexpr std::size_t allocation_alignment = 256;

namespace detail {
// "gpusolve: <who> could not allocate <bytes> bytes for <label> (<why>)".
inline std::string oom_message(const char* who, std::size_t bytes, const std::string& why) {
  std::ostringstream os;
  os << "gpusolve: " << who << " could not allocate " << bytes << " bytes";
  if (const char* label = AllocationLabel::now()) os << " for " << label;
  if (!why.empty()) os << " (" << why << ')';
  return os.str();
}
}  // namespace detail

}  // namespace gpusolve::memory
