// Every solver method on the GPU against the CPU backend: contact colouring,
// coloured Gauss-Seidel, APGD, substepping and APGD with CG steps: solves and World steps with the cone model.
#include <cmath>
#include <cstdint>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"
#include "../../bench/shared_pile.hpp"

using namespace rbd_test;

TEST_CASE("GPU contact colouring equals the CPU's", "[rbd_methods][gpu]") {
  // A sphere pile (one point per pair) and a box pyramid (four per face: pairs coloured).
  const auto colour = [](auto device, rbd::BodySet<float> set, float margin) {
    using Device = decltype(device);
    BodyManager<Device, float> m(set);
    m.syncDeviceFull();
    Contacts<Device, float, ConeFriction> c;
    CollisionDetection<Device, float> cd;
    cd.detect(m.device(), c, margin);
    ContactColouring<Device> col;
    col.build(m.device().view(), c.view());
    std::vector<std::uint32_t> out(c.size());
    if constexpr (std::is_same_v<Device, device::gpu>)
      GPUSOLVE_CUDA_CHECK(cudaMemcpy(out.data(), col.order(), c.size() * 4, cudaMemcpyDeviceToHost));
    else
      std::copy(col.order(), col.order() + c.size(), out.begin());
    out.push_back(std::uint32_t(col.colours()));
    out.push_back(std::uint32_t(col.offset(col.colours())));  // pairs coloured
    return out;
  };
  const auto spheres = pile<float>(6, 5);
  const auto cpu = colour(device::cpu{}, spheres, 0.02f);
  const auto gpu = colour(device::gpu{}, spheres, 0.02f);
  REQUIRE(cpu.size() > 500);
  CHECK(cpu[cpu.size() - 2] >= 6);
  CHECK(cpu.back() == cpu.size() - 2);  // every sphere contact is a pair of its own
  CHECK(gpu == cpu);  // same colours, same order: the colouring is deterministic on both
  const auto boxes = gpusolve::bench::box_pyramid<float>(12);
  const auto cpu_boxes = colour(device::cpu{}, boxes, 0.1f);
  const auto gpu_boxes = colour(device::gpu{}, boxes, 0.1f);
  REQUIRE(cpu_boxes.size() > 300);
  CHECK(cpu_boxes.back() * 3 < cpu_boxes.size());  // most pairs hold four points
  CHECK(gpu_boxes == cpu_boxes);
}

namespace {

// Tolerance as for Jacobi (test_rbd_solver.cu): float rounding and FMA
// contraction differ by a few ulps per iteration; Gauss-Seidel sweeps in the
// same order on both backends, so 300 iterations stay far below 1e-4 m/s.
constexpr float vel_tol = 1e-4f;

template <class Device>
std::vector<float> gs_velocities(const SolverSettings<float>& s, SolverStats<float>& stats) {
  auto set = pile<float>(3, 3);
  BodyManager<Device, float> m(set);
  m.syncDeviceFull();
  Contacts<Device, float, ConeFriction> c;
  prepare_solve(m.device(), c, s);
  stats = ColouredGaussSeidelSolver<Device, float, ConeFriction>().solve(m.device(), c, s);
  Bodies<device::cpu, float> host;
  host = m.device();
  return velocities(host);
}

}  // namespace

TEST_CASE("GPU coloured Gauss-Seidel matches the CPU backend", "[rbd_methods][gpu]") {
  SolverSettings<float> s;
  s.dt = 0.01f, s.margin = 0.02f, s.friction = 0.4f;
  s.tolerance = 1e-12f;  // never reached: both run max_iterations
  s.max_iterations = 300, s.check_every = 50, s.divergence_checks = 0;
  SolverStats<float> cpu_stats, gpu_stats;
  const auto cpu = gs_velocities<device::cpu>(s, cpu_stats);
  const auto gpu = gs_velocities<device::gpu>(s, gpu_stats);
  REQUIRE(cpu_stats.contacts > 50);
  CHECK(gpu_stats.contacts == cpu_stats.contacts);
  CHECK(gpu_stats.colours == cpu_stats.colours);
  CHECK(gpu_stats.iterations == cpu_stats.iterations);
  CHECK(max_abs_diff(gpu, cpu) < vel_tol);
}

TEST_CASE("GPU World with the default method and model matches the CPU backend", "[rbd_methods][gpu]") {
  auto run = [&](auto device) {
    using Device = decltype(device);
    auto set = pile<float>(3, 3);
    SolverSettings<float> s;
    s.friction = 0.4f, s.margin = 0.02f;
    // Solved to a residual of 1e-5 m/s: the default method's momentum restarts may
    // differ between backends (see the APGD test), its solutions do not.
    s.tolerance = 1e-5f, s.max_iterations = 5000, s.check_every = 10;
    World<Device, float> w(set, s);  // ConeFriction, APGD, warm start
    for (int i = 0; i < 3; ++i) REQUIRE(w.step().solver.status != SolverStatus::diverged);
    Bodies<device::cpu, float> host;
    host = w.bodies();
    return velocities(host);
  };
  const auto cpu = run(device::cpu{});
  const auto gpu = run(device::gpu{});
  CHECK(max_abs_diff(gpu, cpu) < 3e-3f);  // three chained steps of the APGD test's bound
}

TEST_CASE("GPU APGD converges to the CPU backend's velocities", "[rbd_methods][gpu]") {
  // Momentum restarts hinge on the sign of a sum that rounds differently on the
  // two backends, so the iterates may part ways; the solutions they converge to
  // do not. Both solve to a residual of 1e-5 m/s (float, 27 spheres).
  auto run = [&](auto device, SolverStats<float>& stats) {
    using Device = decltype(device);
    auto set = pile<float>(3, 3);
    BodyManager<Device, float> m(set);
    m.syncDeviceFull();
    Contacts<Device, float, Frictionless> c;
    SolverSettings<float> s;
    s.dt = 0.01f, s.margin = 0.02f, s.tolerance = 1e-5f, s.max_iterations = 5000, s.check_every = 10;
    prepare_solve(m.device(), c, s);
    stats = JacobiSolver<Device, float, Frictionless, Gather, Nesterov>().solve(m.device(), c, s);
    Bodies<device::cpu, float> host;
    host = m.device();
    return velocities(host);
  };
  SolverStats<float> cpu_stats, gpu_stats;
  const auto cpu = run(device::cpu{}, cpu_stats);
  const auto gpu = run(device::gpu{}, gpu_stats);
  REQUIRE(cpu_stats.status == SolverStatus::converged);
  CHECK(gpu_stats.status == SolverStatus::converged);
  CHECK(max_abs_diff(gpu, cpu) < 1e-3f);  // two solutions within 1e-5 m/s residual of one LCP
}

namespace {

// The velocities after three converged World steps of Method on a cone-friction pile.
template <class Method, class Device>
std::vector<float> converged_steps(Device) {
  auto set = pile<float>(3, 3);
  SolverSettings<float> s;
  s.friction = 0.4f, s.margin = 0.02f;
  s.tolerance = 1e-5f, s.max_iterations = 20000, s.check_every = 10;  // converged, as in the APGD test
  World<Device, float, ConeFriction, Method> w(set, s);
  for (int i = 0; i < 3; ++i) REQUIRE(w.step().solver.status == SolverStatus::converged);
  Bodies<device::cpu, float> host;
  host = w.bodies();
  return velocities(host);
}

}  // namespace

TEST_CASE("GPU substepping World steps converge to the CPU backend's", "[rbd_methods][gpu]") {
  const auto cpu = converged_steps<Substepping<>>(device::cpu{});
  CHECK(max_abs_diff(converged_steps<Substepping<>>(device::gpu{}), cpu) < 3e-3f);
}

TEST_CASE("GPU AcceleratedCG World steps converge to the CPU backend's", "[rbd_methods][gpu]") {
  const auto cpu = converged_steps<AcceleratedCG>(device::cpu{});
  CHECK(max_abs_diff(converged_steps<AcceleratedCG>(device::gpu{}), cpu) < 3e-3f);
}

TEST_CASE("GPU World with materials (pair friction, restitution) matches the CPU backend", "[rbd_methods][gpu][materials]") {
  std::size_t bouncing = 0;
  auto run = [&](auto device) {
    using Device = decltype(device);
    auto set = pile<float>(3, 3);
    const std::uint32_t rubber = set.add_material({0.2f, 0.7f}), felt = set.add_material({0.9f, 0.f});
    set.set_material_pair(rubber, felt, {0.6f, 0.3f});
    for (std::size_t i = 1; i < set.size(); ++i) {
      set.set_material(i, i % 2 ? rubber : felt);
      set[i].v = {0.f, 0.f, -3.f};  // every sphere meets the floor or another at 3 m/s: they bounce
    }
    SolverSettings<float> s;
    s.margin = 0.02f, s.tolerance = 1e-5f, s.max_iterations = 5000, s.check_every = 10;
    World<Device, float> w(set, s);
    REQUIRE(w.step().solver.status != SolverStatus::diverged);
    VectorD1<float, device_is<device::cpu>> bounce;  // empty: takes the store's shape
    bounce = w.contacts().bounce;
    bouncing = 0;
    for (std::size_t k = 0; k < w.contacts().size(); ++k) bouncing += bounce(k) > 0;
    for (int i = 0; i < 2; ++i) REQUIRE(w.step().solver.status != SolverStatus::diverged);
    Bodies<device::cpu, float> host;
    host = w.bodies();
    return velocities(host);
  };
  const auto cpu = run(device::cpu{});
  const std::size_t cpu_bouncing = bouncing;
  const auto gpu = run(device::gpu{});
  CHECK(cpu_bouncing > 0);
  CHECK(bouncing == cpu_bouncing);
  CHECK(max_abs_diff(gpu, cpu) < 3e-3f);
}

TEST_CASE("GPU World with rolling and spinning resistance matches the CPU backend", "[rbd_methods][gpu][rolling]") {
  // ConeRollingFriction: the angular rows through every kernel of the default
  // method and of coloured Gauss-Seidel, on spheres spun about all axes.
  auto run = [&](auto device, auto method) {
    using Device = decltype(device);
    auto set = pile<float>(3, 3);
    const std::uint32_t sticky = set.add_material({0.6f, 0.f, 0.05f, 0.02f});
    for (std::size_t i = 1; i < set.size(); ++i) {
      if (i % 2) set.set_material(i, sticky);
      set[i].w = {float(i % 3) - 1.f, float(i % 5) - 2.f, 3.f};
    }
    SolverSettings<float> s;
    s.margin = 0.02f, s.tolerance = 1e-5f, s.max_iterations = 20000, s.check_every = 10;
    s.rolling = 0.01f, s.spinning = 0.03f;
    World<Device, float, ConeRollingFriction, decltype(method)> w(set, s);
    for (int i = 0; i < 3; ++i) REQUIRE(w.step().solver.status == SolverStatus::converged);
    Bodies<device::cpu, float> host;
    host = w.bodies();
    return velocities(host);
  };
  CHECK(max_abs_diff(run(device::gpu{}, AcceleratedJacobi<Gather>{}), run(device::cpu{}, AcceleratedJacobi<Gather>{})) <
        3e-3f);
  CHECK(max_abs_diff(run(device::gpu{}, ColouredGaussSeidel{}), run(device::cpu{}, ColouredGaussSeidel{})) < 1e-3f);
}
