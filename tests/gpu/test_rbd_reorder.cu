// Spatial order on the GPU (World::reorder_bodies): the same slots as the CPU
// backend's from the same state, and a World reordered every few steps steps
// as one that is not (in double, to the order of its sums); a box heap's state survives a reorder.
#include <algorithm>
#include <cmath>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"

using namespace rbd_test;

TEST_CASE("GPU reorder_bodies: the slots of the CPU backend, and the steps of a World without it",
          "[rbd_reorder][gpu]") {
  BodySet<float> gpu_set = shuffled(pile<float>(6, 4), 5), cpu_set = gpu_set;
  World<device::gpu, float> gpu(gpu_set, SolverSettings<float>{});
  World<device::cpu, float> cpu(cpu_set, SolverSettings<float>{});
  gpu.reorder_bodies(), cpu.reorder_bodies();
  for (std::size_t i = 0; i < gpu_set.size(); ++i) REQUIRE(gpu.manager().slot(i) == cpu.manager().slot(i));
  // In double and solved to 1e-8, as the host test: float at 50 iterations
  // differs by the order of its sums alone (7e-4 m after 30 steps of this pile
  // on an H100), which would hide nothing a wrong slot does.
  SolverSettings<double> s;
  s.max_iterations = 400, s.check_every = 1, s.tolerance = 1e-8;
  SolverSettings<double> every = s;
  every.reorder_every = 5;
  BodySet<double> ordered_set = shuffled(pile<double>(6, 4), 5), plain_set = ordered_set;
  World<device::gpu, double> ordered(ordered_set, every), plain(plain_set, s);
  ordered.advance(30), plain.advance(30);
  const auto a = positions(ordered, ordered_set), b = positions(plain, plain_set);
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, double(std::fabs(a[i] - b[i])));
  INFO("largest difference of a position after 30 steps: " << d);
  CHECK(d < 1e-6);
  CHECK(ordered.latest_stats().solver.contacts == plain.latest_stats().solver.contacts);
}

TEST_CASE("GPU reorder_bodies: a heap of every shape keeps its state and indices", "[rbd_reorder][gpu][shapes]") {
  BodySet<float> set = shuffled(mixed_heap<float>(4, 3), 9);
  World<device::gpu, float> w(set, SolverSettings<float>{});
  w.advance(50);
  const auto before = positions(w, set);
  w.reorder_bodies();
  CHECK(positions(w, set) == before);
  w.advance(50);
  CHECK(w.latest_stats().max_penetration < 0.05f);
}
