// The queued time step on the GPU: queued steps equal steps one by one, late
// statistics equal those read at once, a NaN in one body's state stops the
// step naming the body and leaves every body as it was, and detection grows
// its lists exactly as the CPU backend does.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"
#include "gpu_step_checks.hpp"

using namespace rbd_test;

TEST_CASE("GPU World: queued steps and late statistics equal steps taken one by one", "[rbd_step][gpu]") {
  auto set_a = pile<float>(5, 4), set_b = set_a;
  World<device::gpu, float> a(set_a, settings()), b(set_b, settings());
  std::vector<StepStats<float>> at_once;
  for (int i = 0; i < 30; ++i) at_once.push_back(a.step());
  b.advance(1);
  for (int i = 1; i < 30; ++i) {
    b.advance(1);
    const auto late = b.previous_stats();
    const auto& now = at_once[std::size_t(i - 1)];
    INFO("step " << i - 1);
    CHECK(late.solver.contacts == now.solver.contacts);
    CHECK(late.solver.iterations == now.solver.iterations);
    CHECK(late.max_penetration == now.max_penetration);
    CHECK(late.kinetic_energy == now.kinetic_energy);
    CHECK(late.potential_energy == now.potential_energy);
  }
  CHECK(at_once.back().solver.contacts > 100);
  CHECK(at_once.back().max_penetration > 0);
  a.syncHost(), b.syncHost();
  CHECK(host_state(set_a) == host_state(set_b));  // the GPU path is deterministic
  b.advance(10);
  for (int i = 0; i < 10; ++i) a.step();
  a.syncHost(), b.syncHost();
  CHECK(host_state(set_a) == host_state(set_b));
}

TEST_CASE("GPU World: CUDA graphs replay exactly the kernels launched one by one", "[rbd_step][gpu][graphs]") {
  auto run = [](auto method, bool graphs, std::size_t check_every) {
    using Method = decltype(method);
    auto set = pile<float>(5, 4);
    SolverSettings<float> s = settings();
    s.graphs = s.detection_graph = graphs;
    s.persistent_max_contacts = 0;  // the persistent kernel would take precedence over graphs
    s.check_every = check_every;  // 50: one graph per solve; 7: a graph per run between checks, the last one short
    World<device::gpu, float, ConeFriction, Method> w(set, s);
    std::vector<std::size_t> iterations;
    for (int i = 0; i < 25; ++i) iterations.push_back(w.step().solver.iterations);
    w.syncHost();
    return std::make_pair(host_state(set), iterations);
  };
  for (std::size_t every : {std::size_t(50), std::size_t(7)}) {
    INFO("check_every " << every);
    const auto apgd = run(AcceleratedJacobi<Gather>{}, true, every);
    CHECK(apgd == run(AcceleratedJacobi<Gather>{}, false, every));
    CHECK(run(Jacobi<UpdateCache>{}, true, every) == run(Jacobi<UpdateCache>{}, false, every));
    CHECK(run(Substepping<>{}, true, every) == run(Substepping<>{}, false, every));
    CHECK(apgd.second.back() > 0);
  }
}

TEST_CASE("GPU World: a NaN in one body's velocity names the body and the step, and moves nothing",
          "[rbd_step][gpu]") {
  auto set = pile<float>(4, 3);
  World<device::gpu, float> w(set, settings());
  w.advance(5);
  w.syncHost();
  const std::vector<float> before = host_state(set);
  const std::size_t victim = 9;
  using BV = typename Bodies<device::gpu, float>::View;
  launch(device::gpu{}, 1, PoisonVelocity<BV>{w.bodies().view(), victim});
  try {
    w.step();
    FAIL("the step ran with a NaN velocity");
  } catch (const NonFiniteStateError& e) {
    CHECK(e.body() == victim);
    CHECK(e.field() == "v");
    CHECK(e.step() == 5);
  }
  w.syncHost();
  const std::vector<float> after = host_state(set);
  REQUIRE(after.size() == before.size());
  std::size_t changed = 0;
  for (std::size_t k = 0; k < after.size(); ++k) changed += !(after[k] == before[k]);
  CHECK(changed == 1);                     // the poisoned component alone
  CHECK(std::isnan(set[victim].v[0]));
}

TEST_CASE("GPU collision detection grows its lists and finds what the CPU finds", "[rbd_step][gpu][collision]") {
  BodySet<float> s;  // 60 spheres overlapping each other and a plane: 1830 contacts
  for (std::size_t i = 0; i < 60; ++i)
    s.add_sphere({0.05f * float(i % 5), 0.05f * float((i / 5) % 4), 0.05f + 0.1f * float(i / 20)}, 0.5f, 1.f);
  s.add_plane({0, 0, 1}, 0.f);
  auto keys = [&](auto device) {
    using Device = decltype(device);
    BodyManager<Device, float> m(s);
    m.syncDeviceFull();
    CollisionDetection<Device, float> cd;
    Contacts<Device, float, Frictionless> c;
    const std::size_t n = cd.detect(m.device(), c, 0.f);
    REQUIRE(cd.detect(m.device(), c, 0.f) == n);  // again, with the grown lists
    std::vector<std::uint32_t> a(n), b(n);
    if constexpr (std::is_same_v<Device, device::gpu>) {
      GPUSOLVE_CUDA_CHECK(cudaMemcpy(a.data(), c.a.data(), n * 4, cudaMemcpyDeviceToHost));
      GPUSOLVE_CUDA_CHECK(cudaMemcpy(b.data(), c.b.data(), n * 4, cudaMemcpyDeviceToHost));
    } else {
      for (std::size_t i = 0; i < n; ++i) a[i] = c.a[i], b[i] = c.b[i];
    }
    std::vector<std::uint64_t> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(pair_key(a[i], b[i]));
    return out;
  };
  const auto cpu = keys(device::cpu{});
  CHECK(cpu.size() == 60 * 59 / 2 + 60);
  CHECK(keys(device::gpu{}) == cpu);
}

TEST_CASE("GPU collision detection's kept graph finds what launching finds, through moves, growth and a new margin",
          "[rbd_step][gpu][collision][graphs]") {
  BodySet<float> s;  // 60 spheres on a plane, first far apart
  for (std::size_t i = 0; i < 60; ++i)
    s.add_sphere({3.f * float(i % 5), 3.f * float((i / 5) % 4), 0.55f + 3.f * float(i / 20)}, 0.5f, 1.f);
  s.add_plane({0, 0, 1}, 0.f);
  BodyManager<device::gpu, float> m(s);
  m.syncDeviceFull();
  CollisionDetection<device::gpu, float> kept, launched;
  kept.set_graphs(true);
  Contacts<device::gpu, float, ConeFriction> ck, cl;
  auto same = [&](float margin) {
    const std::size_t n = launched.detect(m.device(), cl, margin, 0.5f);
    REQUIRE(kept.detect(m.device(), ck, margin, 0.5f) == n);
    Contacts<device::cpu, float, ConeFriction> hk, hl;
    hk.a = ck.a, hk.b = ck.b, hk.phi0 = ck.phi0, hk.n = ck.n;
    hl.a = cl.a, hl.b = cl.b, hl.phi0 = cl.phi0, hl.n = cl.n;
    for (std::size_t i = 0; i < n; ++i) {
      INFO("contact " << i);
      REQUIRE(hk.a(i) == hl.a(i));
      REQUIRE(hk.b(i) == hl.b(i));
      REQUIRE(hk.phi0(i) == hl.phi0(i));
      for (int k = 0; k < 3; ++k) REQUIRE(hk.n(i, k) == hl.n(i, k));
    }
    return n;
  };
  // Sizing run, capture, then the kept graph twice.
  for (int k = 0; k < 4; ++k) CHECK(same(0.1f) == 20);
  // The spheres move within their storage: the kept graph sees the new positions.
  for (std::size_t i = 0; i < 20; ++i) s[i].pos[2] = 0.45f;
  m.syncDevice();
  CHECK(same(0.1f) == 20);
  // All overlap: 1 830 contacts, past the contact list's first capacity (4 per body).
  for (std::size_t i = 0; i < 60; ++i)
    s[i].pos = {0.05f * float(i % 5), 0.05f * float((i / 5) % 4), 0.05f + 0.1f * float(i / 20)};
  m.syncDevice();
  for (int k = 0; k < 3; ++k) CHECK(same(0.1f) == 60 * 59 / 2 + 60);
  // Apart again, then a new margin, a new key: every sphere reaches the plane and its neighbours.
  for (std::size_t i = 0; i < 60; ++i)
    s[i].pos = {3.f * float(i % 5), 3.f * float((i / 5) % 4), 0.55f + 3.f * float(i / 20)};
  m.syncDevice();
  CHECK(same(0.1f) == 20);
  CHECK(same(10.f) > 200);
}
