// The CPU backend of the launch layer: every index visited exactly once.
#include <atomic>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/core/launch.hpp"

TEST_CASE("cpu launch visits every index once", "[launch]") {
  for (std::size_t n : {0u, 1u, 31u, 32u, 33u, 1000u}) {
    std::vector<std::atomic<int>> hits(n);
    gpusolve::launch(gpusolve::device::cpu{}, n, [&hits](std::size_t i) { hits[i]++; });
    for (std::size_t i = 0; i < n; ++i) REQUIRE(hits[i].load() == 1);
  }
}

#if !GPUSOLVE_HAS_NVCC
TEST_CASE("gpu launch without nvcc is a typed error", "[launch]") {
  REQUIRE_THROWS_AS(gpusolve::launch(gpusolve::device::gpu{}, 4, [](std::size_t) {}),
                    gpusolve::UnsupportedError);
}
#endif
