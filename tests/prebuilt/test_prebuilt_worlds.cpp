// A program linked to the prebuilt Worlds (gpusolve::worlds): its World and
// SphereWorld steps come from the library, not from this translation unit
// (prebuilt_worlds.hpp), and step the README's scene as the headers do.
#include "catch_compat.hpp"
#include "gpusolve/rbd.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;

#if !defined(GPUSOLVE_PREBUILT_WORLDS)
#error "this test links gpusolve::worlds, which defines GPUSOLVE_PREBUILT_WORLDS"
#endif

namespace {
template <class W>
void readme_scene_rests() {
  BodySet<float> set;
  set.add_plane({0, 0, 1}, 0);
  for (int i = 0; i < 32; ++i)
    set.add_sphere({2.1f * (i % 4), 2.1f * (i / 4 % 4), 1.1f + 2.1f * (i / 16)}, 1.0f, 1.0f);
  SolverSettings<float> settings;
  settings.friction = 0.5f;
  W world(set, settings);
  world.advance(400);
  const StepStats<float> s = world.latest_stats();
  CHECK(s.solver.contacts >= 32);
  CHECK(s.max_penetration < 0.01f);
  world.syncHost();
  for (std::size_t i = 1; i < set.size(); ++i) CHECK(set[i].pos[2] > 0.98f);
}
}  // namespace

TEST_CASE("the prebuilt World and SphereWorld step the README's scene on the CPU backend", "[prebuilt]") {
  readme_scene_rests<World<device::cpu>>();
  readme_scene_rests<SphereWorld<device::cpu>>();
}
