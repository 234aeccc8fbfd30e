// Host-to-device copy bandwidth from pinned vs pageable gpusolve containers.
// Build: nvcc -std=c++17 -O2 -arch=sm_90 -I include bench/bandwidth.cu -o bandwidth
// Run:   ./bandwidth [repeats=25]
// Each size is copied once to warm up, then timed `repeats` times with CUDA
// events around a synchronous assignment (dst = src); the table gives the median
// and the spread (min..max) in GB/s (1e9 bytes/s) and names the GPU.
#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "gpusolve/containers.hpp"

namespace {
using namespace gpusolve;

struct Stats {
  double median, min, max;
};

Stats summarize(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return {median, v.front(), v.back()};
}

// GB/s of `repeats` timed host-to-device copies of `src`.
template <class Host>
Stats measure(const Host& src, int repeats) {
  VectorD1<float, device::gpu> dst(src.size());
  dst = src;  // warm-up: first-touch, driver staging buffers
  GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
  cudaEvent_t start, stop;
  GPUSOLVE_CUDA_CHECK(cudaEventCreate(&start));
  GPUSOLVE_CUDA_CHECK(cudaEventCreate(&stop));
  std::vector<double> gbps;
  for (int r = 0; r < repeats; ++r) {
    GPUSOLVE_CUDA_CHECK(cudaEventRecord(start));
    dst = src;
    GPUSOLVE_CUDA_CHECK(cudaEventRecord(stop));
    GPUSOLVE_CUDA_CHECK(cudaEventSynchronize(stop));
    float ms = 0;
    GPUSOLVE_CUDA_CHECK(cudaEventElapsedTime(&ms, start, stop));
    gbps.push_back(static_cast<double>(src.size() * sizeof(float)) / (ms * 1e-3) / 1e9);
  }
  GPUSOLVE_CUDA_CHECK(cudaEventDestroy(start));
  GPUSOLVE_CUDA_CHECK(cudaEventDestroy(stop));
  // The timed copies must have moved the data: check a few elements.
  VectorD1<float> back(dst);
  for (std::size_t i = 0; i < src.size(); i += src.size() / 7 + 1)
    if (back(i) != src(i)) {
      std::fprintf(stderr, "bandwidth: copy check failed at %zu\n", i);
      std::exit(1);
    }
  return summarize(gbps);
}

template <class Host>
void fill_random(Host& h) {
  std::mt19937 gen(42);
  std::uniform_real_distribution<float> dist(-1.f, 1.f);
  for (auto& x : h) x = dist(gen);
}
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 25;
  try {
    int dev = 0;
    GPUSOLVE_CUDA_CHECK(cudaGetDevice(&dev));
    cudaDeviceProp prop{};
    GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&prop, dev));
    std::printf("GPU: %s (sm_%d%d), host-to-device, %d repeats after one warm-up\n", prop.name, prop.major,
                prop.minor, repeats);
    std::printf("%10s  %-9s  %12s  %22s\n", "size MiB", "host", "median GB/s", "spread (min..max) GB/s");
    for (std::size_t mib : {1u, 16u, 256u}) {
      const std::size_t n = mib * 1024 * 1024 / sizeof(float);
      VectorD1<float> pageable(n);
      VectorD1<float, allocator_is<memory::CUDAHostAllocator>> pinned(n);
      fill_random(pageable);
      pinned = pageable;
      const Stats a = measure(pageable, repeats);
      const Stats b = measure(pinned, repeats);
      std::printf("%10zu  %-9s  %12.2f  %10.2f..%-10.2f\n", mib, "pageable", a.median, a.min, a.max);
      std::printf("%10zu  %-9s  %12.2f  %10.2f..%-10.2f\n", mib, "pinned", b.median, b.min, b.max);
    }
  } catch (const gpusolve::Error& e) {
    std::fprintf(stderr, "bandwidth: %s\n", e.what());
    return 1;
  }
  return 0;
}
