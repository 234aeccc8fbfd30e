// Named container parameters: every order gives the same configuration, defaults, and the checks behind the static_asserts.
#include <array>
#include <cstddef>
#include <tuple>
#include <type_traits>
#include <utility>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

namespace {

using namespace gpusolve;

// A user allocator, so the test does not depend on the CUDA runtime.
struct UserAllocator {
  using memory = memory::host;
  static void* allocate(std::size_t b) { return gpusolve::memory::StandardAllocator::allocate(b); }
  static void deallocate(void* p, std::size_t b) noexcept { gpusolve::memory::StandardAllocator::deallocate(p, b); }
};

// The p-th permutation (lexicographic) of 0..N-1.
template <std::size_t N>
constexpr std::array<std::size_t, N> nth_permutation(std::size_t p) {
  std::array<std::size_t, N> pool{}, out{};
  for (std::size_t i = 0; i < N; ++i) pool[i] = i;
  std::size_t remaining = N;
  for (std::size_t k = 0; k < N; ++k) {
    std::size_t f = 1;
    for (std::size_t m = 2; m < remaining; ++m) f *= m;
    const std::size_t idx = p / f;
    p %= f;
    out[k] = pool[idx];
    for (std::size_t m = idx; m + 1 < remaining; ++m) pool[m] = pool[m + 1];
    --remaining;
  }
  return out;
}

constexpr std::size_t factorial(std::size_t n) { return n < 2 ? 1 : n * factorial(n - 1); }

template <class Tuple, std::size_t P, std::size_t... I>
auto permuted(std::index_sequence<I...>)
    -> ContainerParams<std::tuple_element_t<nth_permutation<sizeof...(I)>(P)[I], Tuple>...>;

template <class Expected, class Tuple, std::size_t... P>
constexpr bool all_orders_agree(std::index_sequence<P...>) {
  constexpr std::size_t N = std::tuple_size_v<Tuple>;
  return (... && std::is_same_v<
                     typename decltype(permuted<Tuple, P>(std::make_index_sequence<N>{}))::device_type,
                     typename Expected::device_type>) &&
         (... && std::is_same_v<
                     typename decltype(permuted<Tuple, P>(std::make_index_sequence<N>{}))::allocator_type,
                     typename Expected::allocator_type>) &&
         (... && std::is_same_v<
                     typename decltype(permuted<Tuple, P>(std::make_index_sequence<N>{}))::layout_type,
                     typename Expected::layout_type>) &&
         (... && std::is_same_v<typename decltype(permuted<Tuple, P>(
                                    std::make_index_sequence<N>{}))::compiletime_policy,
                                typename Expected::compiletime_policy>) &&
         (... && std::is_same_v<
                     typename decltype(permuted<Tuple, P>(std::make_index_sequence<N>{}))::runtime_policy,
                     typename Expected::runtime_policy>);
}

struct Expected5 {
  using device_type = device::cpu;
  using allocator_type = UserAllocator;
  using layout_type = layout::PadAll<16, 8>;
  using compiletime_policy = compiletime::DebugPolicy;
  using runtime_policy = runtime::InfoPolicy;
};

}  // namespace

TEST_CASE("all 120 orders of five named parameters give one configuration", "[container]") {
  using Five = std::tuple<device_is<device::cpu>, allocator_is<UserAllocator>, layout_is<layout::PadAll<16, 8>>,
                          compiletime_policy_is<compiletime::DebugPolicy>, runtime_policy_is<runtime::InfoPolicy>>;
  STATIC_REQUIRE(all_orders_agree<Expected5, Five>(std::make_index_sequence<factorial(5)>{}));
  // The bare device tag and the thesis spellings in every order too.
  using Thesis = std::tuple<device::cpu, MemoryLayout_is<layout::PadAll<16, 8>>,
                            CompiletimePolicy_is<compiletime::DebugPolicy>, runtime_policy_is<runtime::InfoPolicy>,
                            allocator_is<UserAllocator>>;
  STATIC_REQUIRE(all_orders_agree<Expected5, Thesis>(std::make_index_sequence<factorial(5)>{}));
}

TEST_CASE("defaults: cpu, standard allocator, rows padded to a warp, release, runtime off", "[container]") {
  using P = ContainerParams<>;
  STATIC_REQUIRE(std::is_same_v<P::device_type, device::cpu>);
  STATIC_REQUIRE(std::is_same_v<P::allocator_type, memory::StandardAllocator>);
  STATIC_REQUIRE(std::is_same_v<P::layout_type, layout::PadFirst<32>>);
  STATIC_REQUIRE(std::is_same_v<P::compiletime_policy, compiletime::ReleasePolicy>);
  STATIC_REQUIRE(std::is_same_v<P::runtime_policy, runtime::Off>);
  STATIC_REQUIRE(std::is_same_v<VectorD2<float>::params::layout_type, layout::PadFirst<32>>);
  // One parameter given leaves the others at their defaults.
  using Q = ContainerParams<compiletime_policy_is<compiletime::DebugPolicy>>;
  STATIC_REQUIRE(std::is_same_v<Q::compiletime_policy, compiletime::DebugPolicy>);
  STATIC_REQUIRE(std::is_same_v<Q::layout_type, layout::PadFirst<32>>);
  STATIC_REQUIRE(std::is_same_v<Q::device_type, device::cpu>);
#if GPUSOLVE_HAS_CUDART
  // A gpu container defaults to cudaMalloc; a bare tag works like device_is.
  STATIC_REQUIRE(std::is_same_v<ContainerParams<device::gpu>::allocator_type, memory::CUDADeviceAllocator>);
  STATIC_REQUIRE(std::is_same_v<ContainerParams<device_is<device::gpu>>::allocator_type, memory::CUDADeviceAllocator>);
  STATIC_REQUIRE(std::is_same_v<VectorD2<double, device::gpu>::memory_kind, memory::device>);
  STATIC_REQUIRE(std::is_same_v<ContainerParams<allocator_is<memory::CUDAHostAllocator>>::memory_kind, memory::pinned>);
#endif
}

TEST_CASE("the checks behind the repeated and unknown parameter assertions", "[container]") {
  // Unknown parameters have no kind; the static_assert in ContainerParams tests for it.
  STATIC_REQUIRE(std::is_void_v<detail::param_kind_t<int>>);
  STATIC_REQUIRE(std::is_void_v<detail::param_kind_t<layout::NoPadding>>);  // a layout must be wrapped
  STATIC_REQUIRE(std::is_same_v<detail::param_kind_t<device::gpu>, param::device_kind>);
  // A bare tag and its named form count as the same property given twice.
  STATIC_REQUIRE(detail::count_kind<param::device_kind, device::cpu, device_is<device::gpu>> == 2);
  STATIC_REQUIRE(detail::count_kind<param::layout_kind, layout_is<layout::NoPadding>, device::cpu> == 1);
  STATIC_REQUIRE(detail::count_kind<param::runtime_kind, device::cpu> == 0);
}
