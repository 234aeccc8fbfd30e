// Where a box pile's deepest overlaps come from: over the last steps of the
// shared cube pile (or the mixed pile), every step's deepest overlap from the
// states (state_penetration.hpp); where it jumps within one step, the box pair
// behind it is explained from its two states: the manifold box_box finds at the
// step's start (the contact the solve had), how deep its points would be after
// the step at the velocities the step ended with (the solve's own, linearised
// view), and the manifold at the step's end. Where the start's points stay
// shallow but the end overlaps deeply, the overlap grew where the solve had no
// point (a feature the start's manifold did not hold), not from the solve.
//
// Run: gpusolve_bench_deepest_pairs [--scene cubes|mixed|rough] [--n 10000] [--steps 2400]
//        [--last 200] [--jump 0.004] [--seed 1] [--backend gpu|cpu] [--csv FILE]
// rough: 16 cubes thrown at 3 m/s, spinning, onto a floor of 64 fixed cubes
// turned at random (shared_pile.hpp, rough_floor; --seed its draws), 400 steps,
// every one of them looked at.
// --jump: a step is explained where the deepest overlap, over the half extent,
// exceeds this and is at least 1.5 times the step before's.
// Prints each explained step and a summary; the CSV has one row per explained step.
#include <cmath>
#include <cstdio>
#include <string>

#include "gpusolve/rbd/collision/pairs/box_box.hpp"
#include "gpusolve/rbd/statistics/state_penetration.hpp"
#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using T = float;

struct Options {
  std::string scene = "cubes", backend = "gpu", csv;
  std::size_t n = 10000;
  long steps = 0, last = 0;  // 0: the scene's (2 400 and 200; rough 400 and 400)
  double jump = 0.004;
  unsigned seed = 1;
};

// Body i of `set` placed as the narrow phase sees it, in double.
rbd::PlacedShape<double> placed(const rbd::BodySet<T>& set, std::size_t i) {
  const auto& b = set[i];
  return rbd::detail::placed(b.pos, math::to_rotation_matrix(math::Quaternion<double>(b.q[0], b.q[1], b.q[2], b.q[3])),
                             b.shape_param);
}

// A manifold of bodies a and b at one state: its smallest gap, and the
// smallest gap its points would have after a step of dt at the velocities
// `moving` holds (a's point minus b's along the normal from b to a): what the
// solve, linearised at these points, made of them.
struct Seen {
  int points = 0;
  bool edge = false;
  double deepest = 0, predicted = 0;  // m
};

Seen see(const rbd::BodySet<T>& at, const rbd::BodySet<T>& moving, std::size_t a, std::size_t b, double dt,
         double margin) {
  const rbd::Manifold<double> m = rbd::box_box<double>(placed(at, a), placed(at, b), margin);
  Seen s;
  s.points = m.count;
  if (m.count == 0) return s;
  s.edge = (m.points[0].feature >> 13) & 1u;
  s.deepest = s.predicted = 1e30;
  const auto velocity = [&](std::size_t i, const math::Vector3<double>& p) {
    const rbd::Body<T>& x = moving[i];
    const math::Vector3<double> r(p[0] - at[i].pos[0], p[1] - at[i].pos[1], p[2] - at[i].pos[2]);
    const math::Vector3<double> w(x.w[0], x.w[1], x.w[2]), v(x.v[0], x.v[1], x.v[2]);
    return math::Vector3<double>(v + w % r);
  };
  for (int k = 0; k < m.count; ++k) {
    const math::Vector3<double>& p = m.points[k].p;
    const double vn = math::dot(math::Vector3<double>(velocity(a, p) - velocity(b, p)), m.n);
    s.deepest = std::fmin(s.deepest, m.points[k].gap);
    s.predicted = std::fmin(s.predicted, m.points[k].gap + vn * dt);
  }
  return s;
}

template <class Dev>
int run(const Options& o) {
  rbd::BodySet<T> set = o.scene == "mixed"   ? bench::mixed_pile<T>(o.n)
                        : o.scene == "rough" ? bench::rough_floor<T>(o.seed)
                                             : bench::cube_pile<T>(o.n);
  rbd::SolverSettings<T> s;
  s.friction = T(0.5);
  rbd::World<Dev, T> world(set, s);
  std::FILE* csv = bench::open_csv(o.csv, "scene,n,step,a,b,before,after,start_edge,start_points,start_gap,"
                                          "start_predicted_gap,end_edge,end_points,end_gap");
  rbd::BodySet<T> start;
  double previous = 0, deepest = 0;
  int explained = 0, unforeseen = 0, edge_starts = 0;
  for (long step = 0; step < o.steps; ++step) {
    if (step >= o.steps - o.last) start = set;  // the state the step starts from (synced below)
    world.step();
    if (step < o.steps - o.last - 1) continue;
    world.syncHost();
    rbd::StatePenetration worst;
    rbd::for_each_state_overlap(set, [&](std::size_t a, std::size_t b, double relative) {
      if (relative > worst.relative) worst = {relative, a, b};
    });
    const bool boxes = set[worst.a].shape == rbd::box && set[worst.b].shape == rbd::box;
    if (step >= o.steps - o.last && boxes && worst.relative > o.jump && worst.relative > 1.5 * previous) {
      const Seen before = see(start, set, worst.a, worst.b, double(s.dt), double(s.margin)),
                 after = see(set, set, worst.a, worst.b, 0, double(s.margin));
      ++explained;
      edge_starts += before.edge;
      unforeseen += before.points > 0 && after.deepest < 0 && before.predicted > 0.5 * after.deepest;
      std::printf("step %ld: bodies %zu and %zu, %.3f%% -> %.3f%%; at the start: %s, %d point(s), gap %.4f m, "
                  "after the step by its velocities %.4f m; at the end: %s, %d point(s), gap %.4f m\n",
                  step, worst.a, worst.b, 100 * previous, 100 * worst.relative, before.edge ? "edge" : "face",
                  before.points, before.deepest, before.predicted, after.edge ? "edge" : "face", after.points,
                  after.deepest);
      if (csv)
        std::fprintf(csv, "%s,%zu,%ld,%zu,%zu,%.6g,%.6g,%d,%d,%.6g,%.6g,%d,%d,%.6g\n", o.scene.c_str(), o.n, step,
                     worst.a, worst.b, previous, worst.relative, int(before.edge), before.points, before.deepest,
                     before.predicted, int(after.edge), after.points, after.deepest);
    }
    if (step >= o.steps - o.last) deepest = std::max(deepest, worst.relative);
    previous = worst.relative;
  }
  if (csv) std::fclose(csv);
  const std::string what = o.scene == "rough" ? "seed " + std::to_string(o.seed) : "n=" + std::to_string(o.n);
  std::printf("%s %s (%s backend): deepest overlap over the last %ld steps %.3f%%; %d jumps explained, %d of them "
              "from an edge contact at the start, %d where the start's points, moved by the step's velocities, are less "
              "than half as deep as the end's overlap\n",
              o.scene.c_str(), what.c_str(), o.backend.c_str(), o.last, 100 * deepest, explained, edge_starts, unforeseen);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const char* usage = "[--scene cubes|mixed|rough] [--n N] [--steps N] [--last N] [--jump X] [--seed N] [--backend gpu|cpu] "
      "[--csv FILE]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene") o.scene = bench::option_value(argc, argv, i);
    else if (a == "--n") o.n = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--steps") o.steps = std::stol(bench::option_value(argc, argv, i));
    else if (a == "--last") o.last = std::stol(bench::option_value(argc, argv, i));
    else if (a == "--jump") o.jump = std::stod(bench::option_value(argc, argv, i));
    else if (a == "--seed") o.seed = unsigned(std::stoul(bench::option_value(argc, argv, i)));
    else if (a == "--backend") o.backend = bench::option_value(argc, argv, i);
    else if (a == "--csv") o.csv = bench::option_value(argc, argv, i);
    else bench::usage_exit(argv[0], usage, a);
  }
  const bool rough = o.scene == "rough";
  if (o.steps == 0) o.steps = rough ? 400 : 2400;
  if (o.last == 0) o.last = rough ? o.steps : 200;
  if ((o.scene != "cubes" && o.scene != "mixed" && !rough) || (o.backend != "gpu" && o.backend != "cpu") ||
      o.last < 1 || o.last > o.steps)
    bench::usage_exit(argv[0], usage, "");
  return o.backend == "cpu" ? run<device::cpu>(o) : run<device::gpu>(o);
}
