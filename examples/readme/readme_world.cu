// The README's "spheres falling into a box" as one program: the file whose
// compile time bench/build_time.sh measures (docs/build_time.md).
#include <cstdio>

#include <gpusolve/rbd.hpp>
using namespace gpusolve::rbd;

int main() {
  BodySet<float> set;
  set.add_plane({0, 0, 1}, 0);
  for (int i = 0; i < 1000; ++i)
    set.add_sphere({2.1f * (i % 10), 2.1f * (i / 10 % 10), 1.1f + 2.1f * (i / 100)}, 1.0f, 1.0f);
  SolverSettings<float> settings;
  settings.friction = 0.5f;
  SphereWorld<gpusolve::device::gpu> world(set, settings);
  for (int k = 0; k < 1000; ++k) world.advance();
  const StepStats<float> s = world.latest_stats();
  world.syncHost();
  std::printf("contacts %u, iterations %u, penetration %.4g of a radius\n", unsigned(s.solver.contacts),
              unsigned(s.solver.iterations), double(s.max_penetration));
}
