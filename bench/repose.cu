// The angle of repose of a poured pile (issues 36, 37): N spheres (radius 1,
// mass 1) or N three-sphere clumps (bench/shared_pile.hpp's clump type:
// spheres of radius 1 on a line 1.2 apart, mass 3) released at rest from a
// column above the floor, so that each layer lands after the one below; each
// friction coefficient of --friction on every contact, and each rolling
// resistance of --rolling (a length: a fraction of the radius; 0: the cone
// model, else ConeRollingFriction), the library's defaults otherwise.
// When the pour has settled, the angle of the pile's flank from its surface.
//
// Run: gpusolve_bench_repose [--kinds spheres,clumps] [--n 2000] [--steps 4000]
//        [--friction 0.5] [--rolling 0] [--backend gpu|cpu] [--csv FILE] [--profile FILE]
// --csv: one row per kind, friction and rolling (the angle and how it was
// found); --profile: each ring's height per row (tools/plot_repose.py draws them).
//
// The column: sites of a square lattice (spacing 2.1 for spheres, 4.5 for
// clumps: each reaches 2.2 from its centre) within a disc of radius 5
// spacings, or wider for more than 25 layers of it (a taller column lands
// fast enough to blast its own pile flat), layer on layer, jittered by up to
// 0.05 (std::mt19937(1)); clumps turned at random (docs/piles.md's draws).
// The surface: the highest centre in each ring of width 2 about the vertical
// axis through the bodies' mean position (parallel to the surface of their
// tops); the flank is the rings whose height lies between 20% and 80% of the
// highest (a layer lying on the floor, its centres at 1, is no flank),
// and the angle is the arctangent of minus the slope of the least-squares
// line through them.
#include <algorithm>
#include <cstdlib>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using T = float;

constexpr double min_disc_radius = 5;  // in lattice spacings
constexpr double max_layers = 25;
constexpr double ring_width = 2;

// The column's radius in lattice spacings: 5, or the disc that holds n bodies
// in 25 layers.
double disc_radius(std::size_t n) {
  return std::max(min_disc_radius, std::sqrt(double(n) / (max_layers * 3.14159265358979)));
}

// The column of n bodies of the kind ("spheres" or "clumps") on the floor z = 0.
rbd::BodySet<T> poured_column(const std::string& kind, std::size_t n) {
  rbd::BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  const bool clumps = kind == "clumps";
  const double s = clumps ? 4.5 : 2.1, z0 = clumps ? 2.3 : 1.1;
  std::vector<std::array<double, 2>> sites;
  const double radius = disc_radius(n);
  const int reach = int(radius);
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      if (i * i + j * j <= radius * radius) sites.push_back({i * s, j * s});
  std::vector<rbd::Part<T>> line;
  for (int k = -1; k <= 1; ++k) line.push_back({rbd::sphere, {T(1), 0, 0, 0}, {T(1.2 * k), 0, 0}, {1, 0, 0, 0}});
  const rbd::CompoundType<T> type = set.add_compound_type(line, T(3));
  bench::RandomTurns turns;
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& xy = sites[k % sites.size()];
    const double layer = double(k / sites.size());
    const std::array<T, 3> at{T(xy[0] + jitter(gen)), T(xy[1] + jitter(gen)), T(z0 + layer * s + jitter(gen))};
    if (clumps)
      set.add_compound(at, type, turns.next<T>());
    else
      set.add_sphere(at, T(1), T(1));
  }
  return set;
}

struct Surface {
  double angle_deg = 0, peak = 0, radius = 0;
  std::size_t flank_rings = 0;
  std::vector<double> top;  // the highest centre per ring
};

// The pile's surface and the angle of its flank (the header's definition).
Surface surface_of(const rbd::BodySet<T>& set) {
  double cx = 0, cy = 0, moving = 0;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set[i].status == rbd::active) cx += set[i].pos[0], cy += set[i].pos[1], moving += 1;
  cx /= moving, cy /= moving;
  Surface s;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (set[i].status != rbd::active) continue;
    const rbd::Body<T>& b = set[i];
    const double r = std::hypot(double(b.pos[0]) - cx, double(b.pos[1]) - cy);
    const double top = double(b.pos[2]);
    const std::size_t ring = std::size_t(r / ring_width);
    if (s.top.size() <= ring) s.top.resize(ring + 1, 0.0);
    s.top[ring] = std::max(s.top[ring], top);
    s.radius = std::max(s.radius, r);
  }
  s.peak = *std::max_element(s.top.begin(), s.top.end());
  double sr = 0, sh = 0, srr = 0, srh = 0;
  for (std::size_t k = 0; k < s.top.size(); ++k) {
    const double h = s.top[k], r = (double(k) + 0.5) * ring_width;
    if (h < 0.2 * s.peak || h > 0.8 * s.peak) continue;
    sr += r, sh += h, srr += r * r, srh += r * h;
    ++s.flank_rings;
  }
  const double m = double(s.flank_rings);
  if (s.flank_rings >= 2) s.angle_deg = std::atan(-(m * srh - sr * sh) / (m * srr - sr * sr)) * 180 / rbd::pi;
  return s;
}

struct Row {
  Surface surface;
  double kinetic, penetration;  // at the last step
};

template <class Dev, class Model>
Row pour(const std::string& kind, std::size_t n, std::size_t steps, double friction, double rolling) {
  rbd::BodySet<T> set = poured_column(kind, n);
  rbd::SolverSettings<T> s;
  s.friction = T(friction);
  s.rolling = T(rolling);
  rbd::World<Dev, T, Model> world(set, s);
  rbd::StepStats<T> st;
  for (std::size_t k = 0; k < steps; ++k) st = world.step();
  world.syncHost();
  return {surface_of(set), double(st.kinetic_energy), double(st.max_penetration)};
}

template <class Dev>
Row pour(const std::string& kind, std::size_t n, std::size_t steps, double friction, double rolling) {
  if (rolling > 0) return pour<Dev, rbd::ConeRollingFriction>(kind, n, steps, friction, rolling);
  return pour<Dev, rbd::ConeFriction>(kind, n, steps, friction, rolling);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> kinds{"spheres", "clumps"};
  std::size_t n = 2000, steps = 4000;
  std::vector<double> frictions{0.5}, rollings{0};
  std::string backend = "gpu", csv, profile;
  const char* usage =
      "[--kinds spheres,clumps] [--n N] [--steps N] [--friction LIST] [--rolling LIST] [--backend gpu|cpu] "
      "[--csv FILE] [--profile FILE]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--kinds") kinds = bench::parse_words(bench::option_value(argc, argv, i));
    else if (a == "--n") n = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--steps") steps = std::stoul(bench::option_value(argc, argv, i));
    else if (a == "--friction") frictions = bench::parse_list<double>(bench::option_value(argc, argv, i));
    else if (a == "--rolling") rollings = bench::parse_list<double>(bench::option_value(argc, argv, i));
    else if (a == "--backend") backend = bench::option_value(argc, argv, i);
    else if (a == "--csv") csv = bench::option_value(argc, argv, i);
    else if (a == "--profile") profile = bench::option_value(argc, argv, i);
    else bench::usage_exit(argv[0], usage, a);
  }
  for (const auto& k : kinds)
    if (k != "spheres" && k != "clumps") bench::usage_exit(argv[0], usage, "--kinds " + k);
  if (backend != "gpu" && backend != "cpu") bench::usage_exit(argv[0], usage, "--backend " + backend);
  const std::string what =
      "gpusolve repose: " + std::to_string(n) + " bodies poured, " + std::to_string(steps) + " steps at dt 0.0025";
  const std::string dev = backend == "gpu" ? bench::print_banner(what.c_str()) : "cpu backend";
  if (backend == "cpu") std::printf("%s (cpu backend)\n", what.c_str());
  std::FILE* out = bench::open_csv(
      csv, "kind,friction,rolling,n,steps,angle_deg,peak,pile_radius,flank_rings,kinetic_energy,max_penetration,device");
  std::FILE* rings = bench::open_csv(profile, "kind,friction,rolling,ring_centre,height");
  for (const auto& kind : kinds)
    for (double friction : frictions)
      for (double rolling : rollings) {
        const Row r = backend == "gpu" ? pour<device::gpu>(kind, n, steps, friction, rolling)
                                       : pour<device::cpu>(kind, n, steps, friction, rolling);
        std::printf("  %-8s friction %g rolling %g: angle %.1f deg (peak %.2f, pile radius %.1f, %zu flank rings), "
                    "kinetic energy %.3g, penetration %.4f%%\n    ring heights:",
                    kind.c_str(), friction, rolling, r.surface.angle_deg, r.surface.peak, r.surface.radius,
                    r.surface.flank_rings, r.kinetic, 100 * r.penetration);
        for (std::size_t k = 0; k < r.surface.top.size(); ++k) {
          std::printf(" %.1f", r.surface.top[k]);
          if (rings)
            std::fprintf(rings, "%s,%g,%g,%.1f,%.4f\n", kind.c_str(), friction, rolling,
                         (double(k) + 0.5) * ring_width, r.surface.top[k]);
        }
        std::printf("\n");
        std::fflush(stdout);
        if (out)
          std::fprintf(out, "%s,%g,%g,%zu,%zu,%.3f,%.4f,%.3f,%zu,%.6g,%.6g,%s\n", kind.c_str(), friction, rolling, n,
                       steps, r.surface.angle_deg, r.surface.peak, r.surface.radius, r.surface.flank_rings, r.kinetic,
                       r.penetration, dev.c_str());
      }
  if (out) std::fclose(out);
  if (rings) std::fclose(rings);
  return 0;
}
