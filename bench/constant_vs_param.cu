// Run time of the audit kernels (tests/audit): plain C++ vs expression
// templates for the vector triad and Eq. (9), and one body with its descriptors
// passed by value, as a __grid_constant__ parameter or in ConstantDeviceMemory.
// Build: nvcc -std=c++17 -O2 -arch=sm_90 -I include bench/constant_vs_param.cu -o constant_vs_param
// Run:   ./constant_vs_param [elements=16777216] [repeats=50]
// Each kernel runs once to warm up, then `repeats` times between CUDA events;
// the table gives the median time (with ConstantDeviceMemory also without
// the descriptor write that each launch does) and the effective bandwidth (bytes the body
// must move: 10 words per triad element, 15 per Eq. (9) element).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "../tests/audit/audit_kernels.cuh"
#include "gpusolve/containers.hpp"

namespace {
using namespace gpusolve;
using namespace gpusolve_audit;

// Median milliseconds of `repeats` calls of launch() between CUDA events.
template <class Launch>
double median_ms(Launch launch, int repeats) {
  launch();
  GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
  cudaEvent_t start, stop;
  GPUSOLVE_CUDA_CHECK(cudaEventCreate(&start));
  GPUSOLVE_CUDA_CHECK(cudaEventCreate(&stop));
  std::vector<double> ms;
  for (int r = 0; r < repeats; ++r) {
    GPUSOLVE_CUDA_CHECK(cudaEventRecord(start));
    launch();
    GPUSOLVE_CUDA_CHECK(cudaEventRecord(stop));
    GPUSOLVE_CUDA_CHECK(cudaEventSynchronize(stop));
    float t = 0;
    GPUSOLVE_CUDA_CHECK(cudaEventElapsedTime(&t, start, stop));
    ms.push_back(t);
  }
  GPUSOLVE_CUDA_CHECK(cudaEventDestroy(start));
  GPUSOLVE_CUDA_CHECK(cudaEventDestroy(stop));
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

void print_row(const char* type, const char* name, double ms, double bytes) {
  std::printf("| %-6s | %-44s | %8.4f | %7.1f |\n", type, name, ms, bytes / (ms * 1e-3) / 1e9);
}

// A launch with Pass::constant_memory includes writing the descriptor (a
// synchronous cudaMemcpyToSymbol); the "kernel only" row writes it once first.
template <class Body>
void row(const char* type, const char* name, const Body& body, Pass pass, int repeats, double bytes) {
  print_row(type, name, median_ms([&] { launch_each_element(body, pass); }, repeats), bytes);
  if (pass == Pass::constant_memory) {
    launch_each_element(body, pass);
    const unsigned blocks = blocks_for(body.size());
    const double ms = median_ms(
        [&] {
          each_element<<<blocks, block>>>(InConstant<Body>{});
          GPUSOLVE_CUDA_CHECK(cudaGetLastError());
        },
        repeats);
    print_row(type, "  (kernel only, descriptor written before)", ms, bytes);
  }
}

template <class T>
void run_type(const char* type, std::size_t n, int repeats) {
  VectorD2<T, device::gpu> a(n, 3), b(n, 3), d(n, 3), p(n, 3), q(n, 3), v(n, 3), r(n, 3), w(n, 3);
  VectorD1<T, device::gpu> c(n);
  for (auto* m : {&b, &d, &q, &v, &r, &w}) m->fill(T(0.5));
  c.fill(T(2));
  const TriadArgs<T> triad{a.view(), b.view(), d.view(), c.view(), Offset3::of(a.view())};
  const ContactArgs<T> contact{p.view(), q.view(), v.view(), r.view(), w.view(), Offset3::of(p.view()),
                               T(0.0025)};
  const double tb = 10.0 * n * sizeof(T), cb = 15.0 * n * sizeof(T);
  row(type, "triad, plain C++", TriadPlain<T>{triad}, Pass::by_value, repeats, tb);
  row(type, "triad, ET, by value", TriadET<T>{triad}, Pass::by_value, repeats, tb);
  row(type, "triad, ET, __grid_constant__", TriadET<T>{triad}, Pass::grid_constant, repeats, tb);
  row(type, "triad, ET, ConstantDeviceMemory", TriadET<T>{triad}, Pass::constant_memory, repeats, tb);
  row(type, "Eq. (9), plain C++", ContactPlain<T>{contact}, Pass::by_value, repeats, cb);
  row(type, "Eq. (9), ET (Global)", ContactET<T>{contact}, Pass::by_value, repeats, cb);
  row(type, "Eq. (9), ET written through (21 loads)", ContactETWriteThrough<T>{contact}, Pass::by_value,
      repeats, cb);
  row(type, "Eq. (9), cached, by value", ContactCached<T>{contact}, Pass::by_value, repeats, cb);
  row(type, "Eq. (9), cached, __grid_constant__", ContactCached<T>{contact}, Pass::grid_constant, repeats, cb);
  row(type, "Eq. (9), cached, ConstantDeviceMemory", ContactCached<T>{contact}, Pass::constant_memory,
      repeats, cb);
}
}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : (std::size_t(1) << 24);
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 50;
  if (n == 0 || repeats <= 0) {
    std::fprintf(stderr, "usage: %s [elements>0] [repeats>0]\n", argv[0]);
    return 2;
  }
  cudaDeviceProp prop{};
  GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
  std::printf("%s, %zu elements, median of %d runs\n\n", prop.name, n, repeats);
  std::printf("| Type   | Kernel                                       | ms       | GB/s    |\n");
  std::printf("|---|---|---|---|\n");
  run_type<float>("float", n, repeats);
  run_type<double>("double", n, repeats);
  return 0;
}
