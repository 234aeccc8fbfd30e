// The GPU backend of the launch layer runs the same functor as the CPU loop.
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/core/launch.hpp"

namespace {
struct Affine {
  int* out;
  GPUSOLVE_HD void operator()(std::size_t i) const { out[i] = static_cast<int>(3 * i + 1); }
};
}  // namespace

TEST_CASE("gpu launch and cpu launch agree for sizes around the block size", "[launch][gpu]") {
  for (std::size_t n : {1u, 255u, 256u, 257u, 1000003u}) {
    int* d = nullptr;
    GPUSOLVE_CUDA_CHECK(cudaMalloc(&d, n * sizeof(int)));
    GPUSOLVE_CUDA_CHECK(cudaMemset(d, 0xff, n * sizeof(int)));
    gpusolve::launch(gpusolve::device::gpu{}, n, Affine{d});
    std::vector<int> got(n), want(n, -7);
    GPUSOLVE_CUDA_CHECK(cudaMemcpy(got.data(), d, n * sizeof(int), cudaMemcpyDeviceToHost));
    GPUSOLVE_CUDA_CHECK(cudaFree(d));
    gpusolve::launch(gpusolve::device::cpu{}, n, Affine{want.data()});
    REQUIRE(got == want);
  }
}

TEST_CASE("a failed CUDA call is reported as a typed CUDA error", "[launch][gpu]") {
  // More shared memory than any GPU offers is refused by the runtime.
  auto kernel = gpusolve::detail::for_each_index_kernel<Affine>;
  REQUIRE_THROWS_AS(GPUSOLVE_CUDA_CHECK(cudaFuncSetAttribute(
                        kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, 1 << 30)),
                    gpusolve::CudaError);
}
