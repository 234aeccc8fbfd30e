// Host <-> device round trips of random data (pinned and pageable, sync and async, sizes on and off
// block multiples), device fill, row alignment of device containers and Thrust interop.
#include <cstddef>
#include <cstdint>
#include <random>

#include <thrust/reduce.h>

#include "catch_compat.hpp"
#include "gpusolve/containers.hpp"

using namespace gpusolve;

namespace {
template <class C>
void fill_random(C& c, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1e6, 1e6);
  for (std::size_t j = 0; j < c.size_y(); ++j)
    for (std::size_t i = 0; i < c.size_x(); ++i) c(i, j) = static_cast<typename C::value_type>(dist(gen));
}

template <class A, class B>
void require_equal(const A& a, const B& b) {
  REQUIRE(a.size_x() == b.size_x());
  REQUIRE(a.size_y() == b.size_y());
  for (std::size_t j = 0; j < a.size_y(); ++j)
    for (std::size_t i = 0; i < a.size_x(); ++i) REQUIRE(a(i, j) == b(i, j));
}

template <class T, class HostAlloc>
void round_trip(std::size_t nx, std::size_t ny, bool async) {
  VectorD2<T, allocator_is<HostAlloc>> src(nx, ny), back(nx, ny);
  fill_random(src, static_cast<unsigned>(nx * 7 + ny));
  VectorD2<T, device::gpu> dev(nx, ny);
  VectorD2<T, device::gpu, layout_is<layout::NoPadding>> dev2(nx, ny);
  if (async) {
    cudaStream_t s;
    GPUSOLVE_CUDA_CHECK(cudaStreamCreate(&s));
    copy_async(dev, src, s);
    copy_async(dev2, dev, s);  // device to device, pitches differ
    copy_async(back, dev2, s);
    GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(s));
    GPUSOLVE_CUDA_CHECK(cudaStreamDestroy(s));
  } else {
    dev = src;
    dev2 = dev;
    back = dev2;
  }
  require_equal(src, back);
}
}  // namespace

TEST_CASE("host -> device -> host round trips keep random data", "[container][gpu]") {
  for (std::size_t nx : {1u, 31u, 32u, 33u, 1000u, 1024u, 4097u}) {
    for (bool async : {false, true}) {
      INFO("nx " << nx << (async ? " async" : " sync"));
      round_trip<double, memory::StandardAllocator>(nx, 3, async);
      round_trip<double, memory::CUDAHostAllocator>(nx, 3, async);
      round_trip<float, memory::StandardAllocator>(nx, 9, async);
      round_trip<float, memory::CUDAHostAllocator>(nx, 9, async);
    }
  }
}

TEST_CASE("an empty device container takes the host's shape; mismatches throw", "[container][gpu]") {
  VectorD2<int> h(70, 4);
  fill_random(h, 3);
  VectorD2<int, device::gpu> d;
  d = h;
  CHECK(d.size_x() == 70);
  CHECK(d.pitch() == 96);
  VectorD2<int> back(d);
  require_equal(h, back);
  VectorD2<int, device::gpu> wrong(70, 5);
  CHECK_THROWS_AS(wrong = h, SizeMismatchError);
}

TEST_CASE("every padded row of a device VectorD2 starts 128-byte aligned", "[container][gpu]") {
  for (std::size_t nx : {1u, 31u, 33u, 65u, 1000u}) {
    VectorD2<float, device::gpu> f(nx, 5);
    VectorD2<double, device::gpu> d(nx, 5);
    for (std::size_t j = 0; j < 5; ++j) {
      CHECK(reinterpret_cast<std::uintptr_t>(f.data() + j * f.pitch()) % 128 == 0);
      CHECK(reinterpret_cast<std::uintptr_t>(d.data() + j * d.pitch()) % 128 == 0);
    }
  }
}

TEST_CASE("device fill and device VectorD3 round trip", "[container][gpu]") {
  VectorD2<float, device::gpu> d(33, 3);
  d.fill(1.25f);
  VectorD2<float> h(d);
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 33; ++i) REQUIRE(h(i, j) == 1.25f);
  d.fill(0.0f);  // the cudaMemset path
  h = d;
  CHECK(h(32, 2) == 0.0f);

  VectorD3<int, layout_is<layout::PadAll<16, 4, 2>>> a(17, 5, 3);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < 17; ++i) a(i, j, k) = int(i * 31 + j * 7 + k * 1000);
  VectorD3<int, device::gpu> g(a);
  VectorD3<int, layout_is<layout::NoPadding>> b(g);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t j = 0; j < 5; ++j)
      for (std::size_t i = 0; i < 17; ++i) REQUIRE(b(i, j, k) == a(i, j, k));
}

TEST_CASE("Thrust algorithms run over a device VectorD1", "[container][gpu]") {
  VectorD1<long long> h(100001);
  long long want = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    h(i) = static_cast<long long>(i * i % 977);
    want += h(i);
  }
  VectorD1<long long, device::gpu> d(h);
  CHECK(thrust::reduce(d.begin(), d.end(), 0LL) == want);
}
