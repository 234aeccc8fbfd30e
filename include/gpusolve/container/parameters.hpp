// Named template parameters of VectorD1/D2/D3, accepted in any order, with defaults.
#pragma once

#include <cstddef>
#include <type_traits>

#include "gpusolve/container/layout.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/memory/allocator.hpp"
#include "gpusolve/memory/cuda_device_allocator.hpp"
#include "gpusolve/memory/standard_allocator.hpp"
#include "gpusolve/policy/compiletime.hpp"
#include "gpusolve/policy/runtime.hpp"

namespace gpusolve {

namespace param {
// One kind tag per property; a parameter says which property it sets.
struct device_kind {};
struct allocator_kind {};
struct layout_kind {};
struct compiletime_kind {};
struct runtime_kind {};
}  // namespace param

template <class D>
struct device_is {
  static_assert(device::is_device_v<D>, "gpusolve: device_is<D> needs device::cpu or device::gpu");
  using gpusolve_param = param::device_kind;
  using type = D;
};
template <class A>
struct allocator_is {
  static_assert(memory::is_allocator_v<A>,
                "gpusolve: allocator_is<A>: A must provide `using memory = host|pinned|device`, "
                "static allocate(bytes) and static deallocate(p, bytes)");
  using gpusolve_param = param::allocator_kind;
  using type = A;
};
template <class L>
struct layout_is {
  static_assert(layout::is_layout_v<L>,
                "gpusolve: layout_is<L>: L must provide static size_t padded(size_t n, int dim)");
  using gpusolve_param = param::layout_kind;
  using type = L;
};
template <class P>
struct compiletime_policy_is {
  using gpusolve_param = param::compiletime_kind;
  using type = P;
};
template <class R>
struct runtime_policy_is {
  using gpusolve_param = param::runtime_kind;
  using type = R;
};

// The thesis's spellings (Listing 1).
template <class L>
using MemoryLayout_is = layout_is<L>;
template <class P>
using CompiletimePolicy_is = compiletime_policy_is<P>;

namespace detail {

// A bare device tag stands for device_is<tag>.
template <class P>
struct normalize_param {
  using type = P;
};
template <>
struct normalize_param<device::cpu> {
  using type = device_is<device::cpu>;
};
template <>
struct normalize_param<device::gpu> {
  using type = device_is<device::gpu>;
};

template <class P, class = void>
struct param_kind {
  using type = void;  // not a named parameter
};
template <class P>
struct param_kind<P, std::void_t<typename P::gpusolve_param>> {
  using type = typename P::gpusolve_param;
};
template <class P>
using param_kind_t = typename param_kind<typename normalize_param<P>::type>::type;

template <class Kind, class... Ps>
inline constexpr int count_kind = (0 + ... + int(std::is_same_v<param_kind_t<Ps>, Kind>));

// The value of the parameter of kind Kind among Ps, or Default when none sets it.
template <class Kind, class Default, class... Ps>
struct find_param {
  using type = Default;
};
template <class Kind, class Default, class P, class... Ps>
struct find_param<Kind, Default, P, Ps...> {
  using type = std::conditional_t<std::is_same_v<param_kind_t<P>, Kind>,
                                  typename normalize_param<P>::type,
                                  typename find_param<Kind, Default, Ps...>::type>;
};
// Stand-in default allocator of device::gpu containers in a build without the
// CUDA runtime; naming such a container is a compile error (see ContainerParams).
struct NoDeviceAllocator {
  using memory = memory::device;
  static void* allocate(std::size_t);
  static void deallocate(void*, std::size_t) noexcept;
};

template <class D>
struct default_allocator {
  using type = memory::StandardAllocator;
};
template <>
struct default_allocator<device::gpu> {
#if GPUSOLVE_HAS_CUDART
  using type = memory::CUDADeviceAllocator;
#else
  using type = NoDeviceAllocator;
#endif
};

}  // namespace detail

// The parsed parameter list: each property looked up by its kind, or its default.
template <class... Ps>
struct ContainerParams {
  static_assert((... && !std::is_void_v<detail::param_kind_t<Ps>>),
                "gpusolve: unknown container parameter; use device_is<>, allocator_is<>, layout_is<>, "
                "compiletime_policy_is<>, runtime_policy_is<> (or a bare device::cpu / device::gpu)");
  static_assert(detail::count_kind<param::device_kind, Ps...> <= 1,
                "gpusolve: the device is given more than once");
  static_assert(detail::count_kind<param::allocator_kind, Ps...> <= 1,
                "gpusolve: the allocator is given more than once");
  static_assert(detail::count_kind<param::layout_kind, Ps...> <= 1,
                "gpusolve: the memory layout is given more than once");
  static_assert(detail::count_kind<param::compiletime_kind, Ps...> <= 1,
                "gpusolve: the compile-time policy is given more than once");
  static_assert(detail::count_kind<param::runtime_kind, Ps...> <= 1,
                "gpusolve: the runtime policy is given more than once");

  using device_type = typename detail::find_param<param::device_kind, device_is<device::cpu>, Ps...>::type::type;
  using allocator_type = typename detail::find_param<
      param::allocator_kind, allocator_is<typename detail::default_allocator<device_type>::type>,
      Ps...>::type::type;
  using layout_type =
      typename detail::find_param<param::layout_kind, layout_is<layout::PadFirst<32>>, Ps...>::type::type;
  using compiletime_policy = typename detail::find_param<
      param::compiletime_kind, compiletime_policy_is<compiletime::ReleasePolicy>, Ps...>::type::type;
  using runtime_policy =
      typename detail::find_param<param::runtime_kind, runtime_policy_is<runtime::Off>, Ps...>::type::type;

  using memory_kind = typename allocator_type::memory;

  static_assert(!std::is_same_v<allocator_type, detail::NoDeviceAllocator>,
                "gpusolve: a device::gpu container needs the CUDA runtime (cuda_runtime_api.h); "
                "this build has none");
  static_assert(std::is_same_v<device_type, device::gpu> == std::is_same_v<memory_kind, memory::device>,
                "gpusolve: the allocator's memory does not match the device: device::cpu needs host or "
                "pinned memory, device::gpu needs device memory");
};

}  // namespace gpusolve
