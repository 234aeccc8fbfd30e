// Test runner shared by the host and GPU suites. The GPU suite is built with
// GPUSOLVE_TESTS_NEED_GPU: without a usable GPU it exits with code 77, which
// ctest reports as skipped, never as passed.
#if __has_include(<catch2/catch.hpp>)
#define CATCH_CONFIG_RUNNER
#endif
#include "catch_compat.hpp"

#if defined(GPUSOLVE_TESTS_NEED_GPU)
#include <cuda_runtime_api.h>
#include <cstdio>
#endif

int main(int argc, char* argv[]) {
#if defined(GPUSOLVE_TESTS_NEED_GPU)
  int count = 0;
  const cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    std::printf("SKIPPED: the GPU suite needs a CUDA GPU; none is usable here (%s)\n",
                e != cudaSuccess ? cudaGetErrorString(e) : "no devices");
    return 77;
  }
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) == cudaSuccess)
    std::printf("gpusolve GPU suite on %s (sm_%d%d)\n", prop.name, prop.major, prop.minor);
#endif
  return Catch::Session().run(argc, argv);
}
