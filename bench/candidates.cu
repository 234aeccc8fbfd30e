// What the pair passes' candidate list holds on a box pile: steps the shared
// cube pile (or the mixed pile) at the defaults and, every --every steps,
// detects its contacts once more apart from the World to count the candidate
// pairs the walk listed (CollisionDetection's summary), the pairs with points
// and the points, beside a hash of the bodies' positions: two builds whose
// hashes agree at every sample took the same steps bit for bit.
//
// Run: gpusolve_bench_candidates [--scene cubes|mixed] [--n 1000] [--steps 1600]
//        [--every 200] [--backend gpu|cpu]
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using T = float;

struct Options {
  std::string scene = "cubes", backend = "gpu";
  std::size_t n = 1000, steps = 1600, every = 200;
};

// FNV-1a over the bits of every body's position.
std::uint64_t position_hash(const rbd::BodySet<T>& set) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < set.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const T x = set[i].pos[c];
      std::uint32_t u;
      std::memcpy(&u, &x, sizeof(u));
      h = (h ^ u) * 1099511628211ull;
    }
  return h;
}

template <class Dev>
int run(const Options& o) {
  rbd::BodySet<T> set = o.scene == "cubes" ? bench::cube_pile<T>(o.n) : bench::mixed_pile<T>(o.n);
  const rbd::SolverSettings<T> s;
  rbd::World<Dev, T> world(set, s);
  rbd::CollisionDetection<Dev, T> detection;
  rbd::Contacts<Dev, T, rbd::ConeFriction> contacts;
  std::printf("gpusolve candidates: %s pile of %zu, defaults, %s backend\n", o.scene.c_str(), o.n, o.backend.c_str());
  std::printf("step,position_hash,candidates,pairs_with_points,points\n");
  double listed = 0, paired = 0;
  std::size_t samples = 0;
  for (std::size_t k = 1; k <= o.steps; ++k) {
    world.advance(1);
    if (k % o.every != 0 && k != o.steps) continue;
    world.manager().syncHost();
    const std::size_t points = detection.detect(world.manager().device(), contacts, s.margin);
    const std::uint32_t candidates = detection.summary().candidates;
    const VectorD1<std::uint32_t> a(contacts.a), b(contacts.b);  // sorted by (a, b)
    std::size_t pairs = 0;
    for (std::size_t p = 0; p < points; ++p) pairs += p == 0 || a(p) != a(p - 1) || b(p) != b(p - 1);
    listed += candidates, paired += double(pairs), ++samples;
    std::printf("%zu,%016llx,%u,%zu,%zu\n", k, static_cast<unsigned long long>(position_hash(world.manager().host())),
                candidates, pairs, points);
  }
  std::printf("candidates per pair with points, over the samples: %.3f\n", listed / paired);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const char* usage = "[--scene cubes|mixed] [--n N] [--steps N] [--every N] [--backend gpu|cpu]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene") o.scene = bench::option_value(argc, argv, i);
    else if (a == "--n") o.n = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--steps") o.steps = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--every") o.every = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--backend") o.backend = bench::option_value(argc, argv, i);
    else bench::usage_exit(argv[0], usage, a);
  }
  if ((o.scene != "cubes" && o.scene != "mixed") || (o.backend != "gpu" && o.backend != "cpu") || o.every == 0 ||
      o.steps == 0)
    bench::usage_exit(argv[0], usage, "");
  return o.backend == "cpu" ? run<device::cpu>(o) : run<device::gpu>(o);
}
