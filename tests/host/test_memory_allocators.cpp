// Allocators: alignment, typed out-of-memory errors, user allocators, and pinned/device memory without a GPU.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
// A user allocator that counts live bytes, to show containers go through it.
struct TrackingAllocator {
  using memory = gpusolve::memory::host;
  static inline std::size_t live_bytes = 0;
  static void* allocate(std::size_t b) {
    live_bytes += b;
    return gpusolve::memory::StandardAllocator::allocate(b);
  }
  static void deallocate(void* p, std::size_t b) noexcept {
    if (p) live_bytes -= b;
    gpusolve::memory::StandardAllocator::deallocate(p, b);
  }
};

#if GPUSOLVE_HAS_CUDART
bool gpu_present() {
  int n = 0;
  const bool ok = cudaGetDeviceCount(&n) == cudaSuccess && n > 0;
  (void)cudaGetLastError();
  return ok;
}
#endif
}  // namespace

TEST_CASE("StandardAllocator returns 256-byte aligned memory and nullptr for 0 bytes", "[memory]") {
  using A = memory::StandardAllocator;
  STATIC_REQUIRE(memory::is_allocator_v<A>);
  STATIC_REQUIRE(!memory::is_allocator_v<int>);
  CHECK(A::allocate(0) == nullptr);
  for (std::size_t b : {1u, 100u, 4096u, 100000u}) {
    void* p = A::allocate(b);
    REQUIRE(p != nullptr);
    CHECK(reinterpret_cast<std::uintptr_t>(p) % memory::allocation_alignment == 0);
    A::deallocate(p, b);
  }
}

TEST_CASE("an impossible host allocation throws OutOfMemoryError naming the bytes", "[memory]") {
  const std::size_t huge = std::numeric_limits<std::size_t>::max() / 2;
  try {
    (void)memory::StandardAllocator::allocate(huge);
    FAIL("no OutOfMemoryError");
  } catch (const OutOfMemoryError& e) {
    CHECK(e.requested_bytes() == huge);
    CHECK(std::string(e.what()).find(std::to_string(huge)) != std::string::npos);
  }
  // An element count whose byte size overflows is reported the same way.
  CHECK_THROWS_AS(VectorD1<double>(std::numeric_limits<std::size_t>::max() / 4), OutOfMemoryError);
}

TEST_CASE("an allocation that fails names what it was for, inside the innermost label", "[memory]") {
  const std::size_t huge = std::numeric_limits<std::size_t>::max() / 2;
  auto message = [&] {
    try {
      (void)memory::StandardAllocator::allocate(huge);
    } catch (const OutOfMemoryError& e) {
      return std::string(e.what());
    }
    return std::string("no OutOfMemoryError");
  };
  CHECK(message().find(" for ") == std::string::npos);  // no label: the bytes and the allocator only
  {
    const memory::AllocationLabel outer("the solver");
    CHECK(message().find(std::to_string(huge) + " bytes for the solver") != std::string::npos);
    {
      const memory::AllocationLabel inner("contacts");
      CHECK(message().find("bytes for contacts") != std::string::npos);
    }
    CHECK(memory::AllocationLabel::now() == std::string("the solver"));  // the inner one ended with its scope
  }
  CHECK(memory::AllocationLabel::now() == nullptr);
}

TEST_CASE("containers allocate and free through a user allocator", "[memory][container]") {
  const std::size_t before = TrackingAllocator::live_bytes;
  {
    VectorD2<float, allocator_is<TrackingAllocator>> a(33, 2);
    CHECK(TrackingAllocator::live_bytes - before == 64 * 2 * sizeof(float));
    a.resize(10, 1);
    CHECK(TrackingAllocator::live_bytes - before == 32 * sizeof(float));
    VectorD2<float> b(10, 1);
    b.fill(3.0f);
    a = b;
    CHECK(a(9, 0) == 3.0f);
  }
  CHECK(TrackingAllocator::live_bytes == before);
}

#if GPUSOLVE_HAS_CUDART
TEST_CASE("pinned memory works with a GPU and throws NoDeviceError without one", "[memory][pinned]") {
  if (gpu_present()) {
    VectorD2<double, allocator_is<memory::CUDAHostAllocator>> p(33, 3);
    p(32, 2) = 1.0;
    CHECK(p(32, 2) == 1.0);
    CHECK(reinterpret_cast<std::uintptr_t>(p.data()) % 128 == 0);
    VectorD2<double> h(33, 3);
    h = p;
    CHECK(h(32, 2) == 1.0);
  } else {
    CHECK_THROWS_AS((VectorD2<double, allocator_is<memory::CUDAHostAllocator>>(33, 3)), NoDeviceError);
    CHECK_THROWS_AS((memory::HostMemory<int, memory::CUDAHostAllocator>(10)), NoDeviceError);
    CHECK_THROWS_AS((VectorD1<float, device::gpu>(10)), NoDeviceError);
    CHECK_THROWS_AS(memory::DeviceMemory<int>(10), NoDeviceError);
    // Empty containers allocate nothing, so they need no GPU.
    VectorD1<float, device::gpu> empty;
    CHECK(empty.data() == nullptr);
  }
}
#endif

TEST_CASE("memory_use counts the bytes containers hold per memory kind, now and at most", "[memory]") {
  using memory::host;
  memory::reset_peak<host>();
  const std::size_t before = memory::memory_use<host>().now;
  {
    VectorD1<double, device_is<device::cpu>> a(1000);
    const std::size_t held = memory::memory_use<host>().now - before;
    CHECK(held >= 1000 * sizeof(double));
    CHECK(held == a.allocated() * sizeof(double));  // padding included
    {
      VectorD1<float, device_is<device::cpu>> b(5000);
      CHECK(memory::memory_use<host>().now - before == held + b.allocated() * sizeof(float));
    }
    CHECK(memory::memory_use<host>().now - before == held);  // b's bytes returned
    const memory::MemoryUse u = memory::memory_use<host>();
    CHECK(u.peak - before >= held + 5000 * sizeof(float));  // b's bytes were held at once with a's
    memory::reset_peak<host>();
    CHECK(memory::memory_use<host>().peak == memory::memory_use<host>().now);
  }
  CHECK(memory::memory_use<host>().now == before);
  // A move hands the bytes over without counting them twice.
  VectorD1<int, device_is<device::cpu>> c(100);
  const std::size_t with_c = memory::memory_use<host>().now;
  VectorD1<int, device_is<device::cpu>> d(std::move(c));
  CHECK(memory::memory_use<host>().now == with_c);
}
