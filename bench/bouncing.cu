// Bouncing balls (issue 37, in the spirit of SimBenchmark's "Bouncing"): 7 x 7
// balls (radius 0.5, mass 1, 2 apart) dropped with their lowest points h = 5
// above a plane, every ball of restitution e (a material of its own; the
// plane keeps the default e = 0, and a pair takes the larger), friction 0.5,
// the library's defaults otherwise. A bounce n's top is the largest gap a
// ball reaches between its n-th and (n+1)-th impacts; its energy over the
// start's is top / h, against e^(2n) for an exact bounce. Impacts slower than
// SolverSettings::bounce_threshold (1 m/s) do not bounce, so a ball of e < 1
// stops after its last fast one.
//
// Run: gpusolve_bench_bouncing [--e 1,0.8,0.5] [--dts 0.0025] [--seconds 12] [--backend gpu|cpu] [--csv FILE]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gpusolve/rbd/world.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using T = float;

constexpr int side = 7;
constexpr double radius = 0.5, height = 5.0;

struct Bounce {
  int n;
  double mean, lowest, highest;  // energy over the start's, over the balls
};

// The tops of every ball's bounces (gap over h), bounce by bounce.
template <class Dev>
std::vector<Bounce> bounces(double e, double seconds, double dt) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  const std::uint32_t ball = set.add_material({T(0.5), T(e)});
  for (int i = 0; i < side * side; ++i)
    set.set_material(set.add_sphere({T(2 * (i % side)), T(2 * (i / side)), T(radius + height)}, T(radius), T(1)),
                     ball);
  rbd::SolverSettings<T> s;
  s.dt = T(dt);
  rbd::World<Dev, T> world(set, s);
  std::vector<std::vector<double>> tops(set.size());  // per ball: its bounces' tops
  std::vector<double> previous(set.size(), height), rising(set.size(), 0);
  for (long k = 0; k * dt < seconds; ++k) {
    world.step();
    world.syncHost();
    for (std::size_t i = 1; i < set.size(); ++i) {
      const double gap = double(set[i].pos[2]) - radius, v = double(set[i].v[2]);
      if (v > 0) rising[i] = 1;
      if (rising[i] != 0 && v <= 0) {  // a top: up until now (a ball at rest, rising by less than 1 cm, is none)
        const double top = std::max(gap, previous[i]);
        if (top > 0.01) tops[i].push_back(top / height);
        rising[i] = 0;
      }
      previous[i] = gap;
    }
  }
  std::vector<Bounce> out;
  for (int n = 1;; ++n) {
    Bounce b{n, 0, 1e30, -1e30};
    std::size_t balls = 0;
    for (std::size_t i = 1; i < set.size(); ++i) {
      if (tops[i].size() < std::size_t(n)) continue;
      const double x = tops[i][n - 1];
      b.mean += x, b.lowest = std::min(b.lowest, x), b.highest = std::max(b.highest, x), ++balls;
    }
    if (balls == 0) return out;
    b.mean /= double(balls);
    out.push_back(b);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> es{1.0, 0.8, 0.5};
  std::vector<double> dts{0.0025};
  double seconds = 12;
  std::string backend = "gpu", csv;
  const char* usage = "[--e LIST] [--dts LIST] [--seconds S] [--backend gpu|cpu] [--csv FILE]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--e") es = bench::parse_list<double>(bench::option_value(argc, argv, i));
    else if (a == "--dts") dts = bench::parse_list<double>(bench::option_value(argc, argv, i));
    else if (a == "--seconds") seconds = std::stod(bench::option_value(argc, argv, i));
    else if (a == "--backend") backend = bench::option_value(argc, argv, i);
    else if (a == "--csv") csv = bench::option_value(argc, argv, i);
    else bench::usage_exit(argv[0], usage, a);
  }
  if (backend != "gpu" && backend != "cpu") bench::usage_exit(argv[0], usage, "--backend " + backend);
  const std::string what = "gpusolve bouncing: 7 x 7 balls dropped from h = 5 for " + std::to_string(seconds) + " s";
  const std::string dev = backend == "gpu" ? bench::print_banner(what.c_str()) : "cpu backend";
  if (backend == "cpu") std::printf("%s (cpu backend)\n", what.c_str());
  std::FILE* out = bench::open_csv(csv, "e,dt,bounce,energy_mean,energy_lowest,energy_highest,exact,relative_error,device");
  for (double dt : dts)
  for (double e : es) {
    const auto rows = backend == "gpu" ? bounces<device::gpu>(e, seconds, dt) : bounces<device::cpu>(e, seconds, dt);
    std::printf("  e = %.2f, dt = %g: %zu bounces\n", e, dt, rows.size());
    for (const Bounce& b : rows) {
      const double exact = std::pow(e, 2 * b.n), err = (b.mean - exact) / exact;
      std::printf("    bounce %2d: energy %.5f of the start (balls %.5f to %.5f), e^2n %.5f, %+.3f%%\n", b.n, b.mean,
                  b.lowest, b.highest, exact, 100 * err);
      if (out)
        std::fprintf(out, "%.3f,%g,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%s\n", e, dt, b.n, b.mean, b.lowest, b.highest, exact, err,
                     dev.c_str());
    }
  }
  if (out) std::fclose(out);
  return 0;
}
