// The contact solver on the GPU against the CPU backend: same scenes, same
// numbers within float tolerance; every accumulation strategy agrees.
#include <cmath>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// Tolerance: float has 6e-8 relative rounding; the GPU contracts to FMAs and sums
// a body's updates in another order (atomics: in any order), so each iteration
// differs by a few ulps of velocities of order 1 m/s. The damped Jacobi iteration
// is a contraction, so these differences do not grow: after a few hundred
// iterations they stay far below 300 * 6e-8 ~ 2e-5 m/s. We allow 1e-4 m/s.
constexpr float vel_tol = 1e-4f;

SolverSettings<float> settings() {
  SolverSettings<float> s;
  s.dt = 0.01f, s.margin = 0.02f, s.omega = 0.5f, s.friction = 0.4f;
  s.tolerance = 1e-12f;  // never reached: every run does max_iterations
  s.max_iterations = 300, s.check_every = 50, s.divergence_checks = 0;
  return s;
}

struct Result {
  std::vector<float> v, x;
  SolverStats<float> stats;
};

template <class Device, class Strategy>
Result solve_pile(const SolverSettings<float>& s) {
  auto set = pile<float>(3, 3);
  BodyManager<Device, float> m(set);
  m.syncDeviceFull();
  Contacts<Device, float, PyramidFriction> c;
  prepare_solve(m.device(), c, s);
  Result r;
  r.stats = JacobiSolver<Device, float, PyramidFriction, Strategy>().solve(m.device(), c, s);
  Bodies<device::cpu, float> host;
  host = m.device();
  r.v = velocities(host);
  VectorD2<float, device_is<device::cpu>> x;
  x = c.x;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) r.x.push_back(x(i, k));
  return r;
}

}  // namespace

TEST_CASE("GPU Jacobi matches the CPU backend for every accumulation strategy", "[rbd_solver][gpu]") {
  const auto s = settings();
  const Result cpu = solve_pile<device::cpu, Gather>(s);
  REQUIRE(cpu.stats.contacts > 50);
  float largest = 0;
  for (float x : cpu.x) largest = std::fmax(largest, x);
  REQUIRE(largest > 0.01f);
  auto check = [&](const Result& gpu) {
    REQUIRE(gpu.stats.contacts == cpu.stats.contacts);  // detection sorts contacts by (a, b) on both
    CHECK(gpu.stats.iterations == cpu.stats.iterations);
    CHECK(max_abs_diff(gpu.v, cpu.v) < vel_tol);
    // Impulses: velocity tolerance times the heaviest inverse block entry (mass 1 bodies: < 1 kg).
    CHECK(max_abs_diff(gpu.x, cpu.x) < vel_tol);
  };
  const Result cache = solve_pile<device::gpu, UpdateCache>(s);
  const Result atomic = solve_pile<device::gpu, Atomic>(s);
  const Result gather = solve_pile<device::gpu, Gather>(s);
  check(cache);
  check(atomic);
  check(gather);
  CHECK(cache.stats.reduction_passes == solve_pile<device::cpu, UpdateCache>(s).stats.reduction_passes);
  CHECK(cache.stats.reduction_passes >= 3);  // a sphere of the pile has 5 to 8 contacts
  CHECK(gather.stats.reduction_passes == 0);
  CHECK(max_abs_diff(cache.v, atomic.v) < vel_tol);
  CHECK(max_abs_diff(cache.v, gather.v) < vel_tol);
  CHECK(max_abs_diff(gather.v, solve_pile<device::gpu, Gather>(s).v) == 0.0f);  // gather is deterministic
}

TEST_CASE("GPU World: resting sphere and rolling on an incline match the CPU backend", "[rbd_physics][gpu]") {
  const float theta = 0.5235988f;  // 30 degrees
  auto run = [&](auto device) {
    using Device = decltype(device);
    BodySet<float> set;
    const std::array<float, 3> n = {-std::sin(theta), 0.f, std::cos(theta)};
    set.add_plane(n, 0);
    set.add_sphere({0.5f * n[0], 0, 0.5f * n[2]}, 0.5f, 1.0f);
    SolverSettings<float> s;
    s.dt = 0.002f, s.margin = 0.02f, s.omega = 0.8f, s.tolerance = 1e-6f, s.friction = 0.5f;
    World<Device, float, PyramidFriction, Jacobi<UpdateCache>> w(set, s);
    for (int i = 0; i < 300; ++i) REQUIRE(w.step().solver.status != SolverStatus::diverged);
    w.syncHost();
    return set[1];
  };
  const auto cpu = run(device::cpu{});
  const auto gpu = run(device::gpu{});
  // Rolling: v = 5/7 g sin(theta) t after t = 0.6 s (first step included).
  const float expected = 5.0f / 7.0f * 9.81f * std::sin(theta) * 0.6f;
  const float speed = std::sqrt(gpu.v[0] * gpu.v[0] + gpu.v[2] * gpu.v[2]);
  CHECK(speed == Approx(expected).epsilon(0.03));
  for (int k = 0; k < 3; ++k) {
    CHECK(gpu.v[k] == Approx(cpu.v[k]).margin(1e-3));  // 300 steps of float rounding in v ~ 2 m/s
    CHECK(gpu.pos[k] == Approx(cpu.pos[k]).margin(1e-3));
  }
}

TEST_CASE("GPU warm-started World steps match the CPU backend", "[rbd_solver][gpu]") {
  auto s = settings();  // 300 iterations every step: both backends do the same work
  s.warm_start = 0.8f;
  auto run = [&](auto device) {
    using Device = decltype(device);
    auto set = pile<float>(3, 3);
    World<Device, float, PyramidFriction, Jacobi<Gather>> w(set, s);
    for (int i = 0; i < 3; ++i) REQUIRE(w.step().solver.status != SolverStatus::diverged);
    Result r;
    Bodies<device::cpu, float> host;
    host = w.bodies();
    r.v = velocities(host);
    VectorD2<float, device_is<device::cpu>> x;
    x = w.contacts().x;
    for (std::size_t i = 0; i < w.contacts().size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) r.x.push_back(x(i, k));
    return r;
  };
  const Result cpu = run(device::cpu{});
  const Result gpu = run(device::gpu{});
  REQUIRE(cpu.x.size() > 150);
  // Each step's solve keeps within vel_tol (above); here three steps chain: the
  // next detection sees positions moved by the differing velocities and the warm
  // start carries last step's impulse difference (unit masses: impulse in m/s),
  // so the bounds add up to 3 vel_tol. Measured on an H100: 1.2e-4 and 2.1e-4.
  const float steps_tol = 3 * vel_tol;
  CHECK(max_abs_diff(gpu.v, cpu.v) < steps_tol);
  CHECK(max_abs_diff(gpu.x, cpu.x) < steps_tol);
}

TEST_CASE("GPU Jacobi reports divergence for omega = 1 on a dense pile", "[rbd_solver][gpu]") {
  auto s = settings();
  s.omega = 1.0f;
  s.divergence_checks = 3;
  s.check_every = 10;
  s.max_iterations = 2000;
  s.max_retries = 0;
  CHECK(solve_pile<device::gpu, UpdateCache>(s).stats.status == SolverStatus::diverged);
  CHECK(solve_pile<device::gpu, Atomic>(s).stats.status == SolverStatus::diverged);
}

TEST_CASE("GPU adaptive under-relaxation restarts like the CPU backend", "[rbd_solver][gpu]") {
  auto s = settings();  // 300 iterations in the last attempt: the runs stay comparable
  s.omega = 1.0f;
  s.divergence_checks = 3;
  s.check_every = 10;
  const Result cpu = solve_pile<device::cpu, Gather>(s);
  REQUIRE(cpu.stats.status != SolverStatus::diverged);
  REQUIRE(cpu.stats.retries >= 1);
  for (const Result& gpu : {solve_pile<device::gpu, Gather>(s), solve_pile<device::gpu, Atomic>(s)}) {
    CHECK(gpu.stats.status == cpu.stats.status);
    CHECK(gpu.stats.retries == cpu.stats.retries);
    CHECK(gpu.stats.omega == cpu.stats.omega);
    CHECK(gpu.stats.iterations == cpu.stats.iterations);
    CHECK(gpu.stats.total_iterations > gpu.stats.iterations);
    CHECK(max_abs_diff(gpu.v, cpu.v) < vel_tol);  // restored on the device: the last attempt starts clean
  }
}

TEST_CASE("GPU residual check: one reduction, same value as the CPU, scratch kept", "[rbd_solver][gpu]") {
  const std::size_t nb = 5000, nc = 12000;
  Bodies<device::cpu, float> hb(nb);
  VectorD1<float, device_is<device::cpu>> hr(nc);
  for (std::size_t i = 0; i < nc; ++i) hr(i) = float((i * 7919) % 1000) * 1e-3f;
  hr(8888) = 2.5f;
  Bodies<device::gpu, float> db;
  db = hb;
  VectorD1<float, device_is<device::gpu>> dr;
  dr = hr;
  ResidualCheck<device::cpu, float> on_cpu;
  ResidualCheck<device::gpu, float> on_gpu;
  CHECK(on_gpu(db.view(), dr.view(), nc) == on_cpu(hb.view(), hr.view(), nc));
  CHECK(on_gpu(db.view(), dr.view(), nc) == 2.5f);
  const std::size_t bytes = on_gpu.scratch_bytes();
  CHECK(bytes > 0);
  CHECK(on_gpu(db.view(), dr.view(), 100) == on_cpu(hb.view(), hr.view(), 100));
  hb.v(nb - 1, 0) = std::nanf("");
  db = hb;
  CHECK(std::isinf(on_gpu(db.view(), dr.view(), nc)));
  CHECK(std::isinf(on_gpu(db.view(), dr.view(), 10)));  // body beyond the contacts
  CHECK(on_gpu.scratch_bytes() == bytes);  // no reallocation from check to check
}
