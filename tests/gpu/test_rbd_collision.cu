// The same random cloud gives identical contacts on the GPU and the CPU, and
// integration agrees within float tolerance.
#include <cstdint>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"
#include "../host/test_rbd_collision_scene.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;

TEST_CASE("GPU and CPU collision detection give the same contacts", "[rbd][collision][gpu]") {
  for (unsigned seed : {11u, 12u}) {
    BodySet<float> s = rbd_test::random_cloud(seed, 4000, 19.f);
    BodyManager<device::cpu> cpu(s);
    BodyManager<device::gpu> gpu(s);
    cpu.syncDevice();
    gpu.syncDevice();
    CollisionDetection<device::cpu> cd_cpu;
    CollisionDetection<device::gpu> cd_gpu;
    Contacts<device::cpu, float, PyramidFriction> c_cpu, c_back;
    Contacts<device::gpu, float, PyramidFriction> c_gpu;
    const float margin = 0.01f;
    const std::size_t n_cpu = cd_cpu.detect(cpu.device(), c_cpu, margin, 0.3f);
    const std::size_t n_gpu = cd_gpu.detect(gpu.device(), c_gpu, margin, 0.3f);
    GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
    REQUIRE(n_cpu > 1000);
    // Pairs within rounding of the margin may differ between backends (FMA); there are none
    // in practice, and a mismatch is reported rather than hidden.
    REQUIRE(n_gpu == n_cpu);
    c_back.a = c_gpu.a;
    c_back.b = c_gpu.b;
    c_back.n = c_gpu.n;
    c_back.phi0 = c_gpu.phi0;
    c_back.ra = c_gpu.ra;
    for (std::size_t k = 0; k < n_cpu; ++k) {
      INFO("seed " << seed << ", contact " << k);
      REQUIRE(c_back.a(k) == c_cpu.a(k));
      REQUIRE(c_back.b(k) == c_cpu.b(k));
      CHECK(c_back.phi0(k) == Approx(c_cpu.phi0(k)).margin(1e-5));
      for (int d = 0; d < 3; ++d) {
        CHECK(c_back.n(k, d) == Approx(c_cpu.n(k, d)).margin(1e-5));
        CHECK(c_back.ra(k, d) == Approx(c_cpu.ra(k, d)).margin(1e-5));
      }
    }
  }
}

TEST_CASE("GPU integration matches the CPU", "[rbd][integrate][gpu]") {
  BodySet<float> s = rbd_test::random_cloud(5, 3000, 30.f);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].status == active) {
      s[i].w = {0.3f, -1.f + 0.001f * float(i % 100), 2.f};
      s[i].torque = {0.01f, 0.f, -0.02f};
    }
  BodyManager<device::cpu> cpu(s);
  BodyManager<device::gpu> gpu(s);
  cpu.syncDevice();
  gpu.syncDevice();
  const math::Vector3<float> g(0.f, 0.f, -9.81f);
  for (int k = 0; k < 100; ++k) {
    integrate(cpu.device(), 0.005f, g);
    integrate(gpu.device(), 0.005f, g);
  }
  Bodies<device::cpu, float> back;
  back = gpu.device();
  auto& c = cpu.device();
  REQUIRE(back.size() == c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    INFO("body " << i);
    for (int d = 0; d < 3; ++d) {
      CHECK(back.pos(i, d) == Approx(c.pos(i, d)).margin(1e-4));
      CHECK(back.v(i, d) == Approx(c.v(i, d)).margin(1e-4));
      CHECK(back.w(i, d) == Approx(c.w(i, d)).margin(1e-4));
    }
    for (int d = 0; d < 4; ++d) CHECK(back.q(i, d) == Approx(c.q(i, d)).margin(1e-4));
    for (int d = 0; d < 6; ++d) CHECK(back.aabb(i, d) == Approx(c.aabb(i, d)).margin(1e-4));
  }
}
