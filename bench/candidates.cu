// What the pair passes' candidate list holds on a box pile: steps the shared
// cube pile (or the mixed pile) at the defaults and, every --every steps,
// detects its contacts once more apart from the World to count the candidate
// pairs the walk listed (CollisionDetection's summary), the pairs with points
// and the points, beside a hash of the bodies' positions: two builds whose
// hashes agree at every sample took the same steps bit for bit.
//
// With --per-body, each sample also counts every body's candidates on the host,
// over all pairs, with the candidate walk's own tests (bounding spheres within
// the margin, a box's slabs, the planes): the most one body lists, and how many
// bodies list more than the walks keep (kept_partners.hpp), who walk twice.
//
// Run: gpusolve_bench_candidates [--scene cubes|mixed] [--n 1000] [--steps 1600]
//        [--every 200] [--backend gpu|cpu] [--per-body]
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
  bool per_body = false;
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

// Every body's candidates (j > i, and the planes) counted over all pairs.
struct PerBody {
  std::uint32_t most = 0;
  std::size_t past_contacts = 0, past_candidates = 0;  // bodies past kept_contacts, past kept_candidates
};
PerBody per_body_candidates(rbd::BodySet<T>& set, T margin) {
  rbd::BodyManager<device::cpu, T> m(set);
  m.syncDevice();
  const auto b = m.device().view();
  PerBody r;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (b.shape[i] == rbd::plane) continue;
    const rbd::detail::GridSphere<T> me = rbd::detail::grid_sphere<decltype(b), T>(b, i);
    const rbd::detail::BoxSlabs<T> slabs(b, i);
    std::uint32_t c = 0;
    for (std::size_t j = 0; j < b.size(); ++j) {
      if (b.shape[j] == rbd::plane) {
        const T along = b.shape_param(j, 0) * me.x[0] + b.shape_param(j, 1) * me.x[1] + b.shape_param(j, 2) * me.x[2];
        c += along - b.shape_param(j, 3) < me.r + margin;
        continue;
      }
      if (j <= i) continue;
      const rbd::detail::GridSphere<T> o = rbd::detail::grid_sphere<decltype(b), T>(b, j);
      c += rbd::detail::spheres_near(me, o, margin) &&
           !(slabs.apart(o, margin) && rbd::detail::slabs_decide(rbd::ShapeKind(b.shape[j])));
    }
    r.most = c > r.most ? c : r.most;
    r.past_contacts += c > rbd::detail::kept_contacts;
    r.past_candidates += c > rbd::detail::kept_candidates;
  }
  return r;
}

template <class Dev>
int run(const Options& o) {
  rbd::BodySet<T> set = o.scene == "cubes" ? bench::cube_pile<T>(o.n) : bench::mixed_pile<T>(o.n);
  const rbd::SolverSettings<T> s;
  rbd::World<Dev, T> world(set, s);
  rbd::CollisionDetection<Dev, T> detection;
  rbd::Contacts<Dev, T, rbd::ConeFriction> contacts;
  std::printf("gpusolve candidates: %s pile of %zu, defaults, %s backend\n", o.scene.c_str(), o.n, o.backend.c_str());
  std::printf("step,position_hash,candidates,pairs_with_points,points%s\n",
              o.per_body ? ",most_of_a_body,bodies_past_kept_contacts,bodies_past_kept_candidates" : "");
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
    std::printf("%zu,%016llx,%u,%zu,%zu", k, static_cast<unsigned long long>(position_hash(world.manager().host())),
                candidates, pairs, points);
    if (o.per_body) {
      const PerBody r = per_body_candidates(set, s.margin);
      std::printf(",%u,%zu,%zu", r.most, r.past_contacts, r.past_candidates);
    }
    std::printf("\n");
  }
  std::printf("candidates per pair with points, over the samples: %.3f\n", listed / paired);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const char* usage = "[--scene cubes|mixed] [--n N] [--steps N] [--every N] [--backend gpu|cpu] [--per-body]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene") o.scene = bench::option_value(argc, argv, i);
    else if (a == "--n") o.n = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--steps") o.steps = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--every") o.every = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--backend") o.backend = bench::option_value(argc, argv, i);
    else if (a == "--per-body") o.per_body = true;
    else bench::usage_exit(argv[0], usage, a);
  }
  if ((o.scene != "cubes" && o.scene != "mixed") || (o.backend != "gpu" && o.backend != "cpu") || o.every == 0 ||
      o.steps == 0)
    bench::usage_exit(argv[0], usage, "");
  return o.backend == "cpu" ? run<device::cpu>(o) : run<device::gpu>(o);
}
