// A kernel reads a container through ConstantDeviceMemory and through a by-value view and gets
// the same numbers; the debug view traps nothing on in-bounds access.
#include <cstddef>
#include <random>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
using Dev = VectorD2<double, device::gpu, compiletime_policy_is<compiletime::DebugPolicy>>;
struct coeff_tag;
using Coeffs = memory::ConstantDeviceMemory<Dev, coeff_tag>;

// out(i) = sum_j in(i, j) * (j + 1), through the constant-memory descriptor.
struct WeightedSumConstant {
  Coeffs in;
  VectorD1View<double> out;
  GPUSOLVE_HD void operator()(std::size_t i) const {
#if GPUSOLVE_DEVICE_CODE
    const auto& v = in.get();
    double s = 0;
    for (std::size_t j = 0; j < v.size_y(); ++j) s += v(i, j) * double(j + 1);
    out[i] = s;
#endif
  }
};

// The same through a view passed by value (a kernel parameter).
struct WeightedSumByValue {
  Dev::view_type in;
  VectorD1View<double> out;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    double s = 0;
    for (std::size_t j = 0; j < in.size_y(); ++j) s += in(i, j) * double(j + 1);
    out[i] = s;
  }
};
}  // namespace

TEST_CASE("ConstantDeviceMemory and a by-value view give the same results", "[container][gpu][constant]") {
  const std::size_t nx = 1000, ny = 4;
  VectorD2<double> h(nx, ny);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) h(i, j) = dist(gen);
  Dev d(h);

  Coeffs c;
  c = d;  // thesis Listing 1: cConst = c;
  const auto stored = c.read();
  CHECK(stored.data() == d.data());
  CHECK(stored.size_x() == nx);
  CHECK(stored.pitch == d.pitch());

  VectorD1<double, device::gpu> r1(nx), r2(nx);
  launch(device::gpu{}, nx, WeightedSumConstant{c, r1.view()});
  launch(device::gpu{}, nx, WeightedSumByValue{d.view(), r2.view()});
  VectorD1<double> a(r1), b(r2), want(nx);
  launch(device::cpu{}, nx, WeightedSumByValue{Dev::view_type{h.data(), nx, ny, h.pitch()}, want.view()});
  for (std::size_t i = 0; i < nx; ++i) {
    REQUIRE(a(i) == b(i));
    REQUIRE(a(i) == Approx(want(i)).epsilon(1e-12));
  }

  // The asynchronous write replaces the descriptor: point it at a second container.
  Dev e(nx, ny);
  e.fill(2.0);
  cudaStream_t s;
  GPUSOLVE_CUDA_CHECK(cudaStreamCreate(&s));
  c.assign_async(e, s);
  launch(device::gpu{}, nx, WeightedSumConstant{c, r1.view()}, s);
  GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(s));
  GPUSOLVE_CUDA_CHECK(cudaStreamDestroy(s));
  a = r1;
  CHECK(a(0) == 2.0 * (1 + 2 + 3 + 4));
  CHECK(a(nx - 1) == 2.0 * (1 + 2 + 3 + 4));
}
