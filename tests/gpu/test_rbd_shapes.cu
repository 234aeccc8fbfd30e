// Every shape on the GPU against the CPU backend: the contacts of a mixed
// heap, and World steps of every method on it.
#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <tuple>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// (a, b, feature, gap) of every contact of a shaken mixed heap.
template <class Device>
std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, float>> heap_contacts() {
  BodySet<float> s = mixed_heap<float>(6, 3);
  s.add_box({2.f, 2.f, 4.f}, {5.f, 0.5f, 0.5f}, 3.f);  // long and moving: the cells follow it
  s.add_fixed_box({2.f, -9.f, 1.f}, {6.f, 6.f, 1.f});  // an obstacle
  BodyManager<Device, float> m(s);
  m.syncDeviceFull();
  CollisionDetection<Device, float> cd;
  Contacts<Device, float, ConeFriction> c;
  const std::size_t n = cd.detect(m.device(), c, 0.05f, 0.5f);
  std::vector<std::uint32_t> a(n), b(n), f(n);
  std::vector<float> gap(n);
  auto copy = [&](auto* dst, const auto* src) {
    if constexpr (std::is_same_v<Device, device::gpu>)
      GPUSOLVE_CUDA_CHECK(cudaMemcpy(dst, src, n * sizeof(*dst), cudaMemcpyDeviceToHost));
    else
      std::copy(src, src + n, dst);
  };
  copy(a.data(), c.a.data());
  copy(b.data(), c.b.data());
  copy(f.data(), c.feature.data());
  copy(gap.data(), c.phi0.data());
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t, float>> out;
  for (std::size_t k = 0; k < n; ++k) out.emplace_back(a[k], b[k], f[k], gap[k]);
  return out;
}

// The velocities after three converged World steps of Method on a mixed heap.
template <class Method, class Device>
std::vector<float> heap_steps(Device) {
  BodySet<float> set = mixed_heap<float>(3, 2);
  SolverSettings<float> s;
  s.friction = 0.4f, s.margin = 0.02f;
  s.tolerance = 1e-5f, s.max_iterations = 20000, s.check_every = 10;
  World<Device, float, ConeFriction, Method> w(set, s);
  for (int i = 0; i < 3; ++i) REQUIRE(w.step().solver.status == SolverStatus::converged);
  Bodies<device::cpu, float> host;
  host = w.bodies();
  return velocities(host);
}

template <class Method>
void require_heap_steps_agree(const char* name) {
  INFO(name);
  const auto cpu = heap_steps<Method>(device::cpu{});
  const auto gpu = heap_steps<Method>(device::gpu{});
  REQUIRE(cpu.size() == gpu.size());
  CHECK(max_abs_diff(gpu, cpu) < 3e-3f);  // converged solutions of one LCP, as for the sphere pile
}

}  // namespace

TEST_CASE("GPU contacts of every shape pair equal the CPU backend's", "[rbd_shapes][gpu]") {
  const auto cpu = heap_contacts<device::cpu>();
  const auto gpu = heap_contacts<device::gpu>();
  REQUIRE(cpu.size() > 100);
  REQUIRE(gpu.size() == cpu.size());
  for (std::size_t k = 0; k < cpu.size(); ++k) {
    INFO("contact " << k);
    CHECK(std::get<0>(gpu[k]) == std::get<0>(cpu[k]));
    CHECK(std::get<1>(gpu[k]) == std::get<1>(cpu[k]));
    CHECK(std::get<2>(gpu[k]) == std::get<2>(cpu[k]));
    CHECK(std::get<3>(gpu[k]) == Approx(std::get<3>(cpu[k])).margin(1e-5));
  }
}

TEST_CASE("GPU World steps of every method on every shape match the CPU backend", "[rbd_shapes][gpu]") {
  require_heap_steps_agree<Jacobi<Gather>>("jacobi");
  require_heap_steps_agree<AcceleratedJacobi<Gather>>("apgd");
  require_heap_steps_agree<ColouredGaussSeidel>("coloured gauss-seidel");
  require_heap_steps_agree<Substepping<>>("substepping");
  require_heap_steps_agree<AcceleratedCG>("apgd-cg");
}

TEST_CASE("GPU unattended steps of a mixed heap match the CPU backend's steps", "[rbd_shapes][gpu]") {
  auto positions = [](auto device) {
    using Device = decltype(device);
    BodySet<float> set = mixed_heap<float>(4, 2);
    SolverSettings<float> s;
    s.detection_graph = true;
    s.tolerance = 1e-5f, s.max_iterations = 20000, s.check_every = 10;  // converged, as above
    World<Device, float, ConeFriction, Jacobi<Gather>> w(set, s);
    w.advance(20);
    w.syncHost();
    std::vector<float> out;
    for (std::size_t i = 0; i < set.size(); ++i)
      for (int c = 0; c < 3; ++c) out.push_back(set[i].pos[c]);
    return out;
  };
  const auto cpu = positions(device::cpu{});
  const auto gpu = positions(device::gpu{});
  CHECK(max_abs_diff(gpu, cpu) < 1e-3f);
}
