// The speed-accuracy atlas: whole time steps of World on the GPU, per scene,
// solver method and iteration budget: time per step against the largest
// penetration and the LCP residual it bought, and whether each step converged.
//
// Run: gpusolve_bench_atlas --scene pile|cubes|mixed|clumps|unions|column|pyramid|stack|field|slabs|hopper [--n 10000,100000] [--ratios 1,100,1000]
//        [--methods gauss-seidel,jacobi,apgd,substepping,apgd-cg]
//        [--budgets default,it10,it20,s4x5,tol0.02,stop0.001,check10,corr0.4,launched,unanchored] [--margins 0.1]
//        [--warm 0.8,1] [--dts 0.0025] [--steps N] [--backend gpu|cpu] [--phases] [--trace N] [--csv FILE]
//
// pile:   the shared pile (bench/shared_pile.hpp, docs/piles.md), N spheres dropped into
//         an open box; 1 200 steps for N <= 10 000, else 900 (docs/piles.md's counts).
// cubes:  the shared cube pile (docs/piles.md), N cubes turned at random; 2 400 steps.
// mixed:  the cube pile's lattice filled with spheres, boxes and capsules in
//         turn (bench/shared_pile.hpp); 2 400 steps.
// clumps: N clumps of three spheres of radius 1 on a line 1.2 apart, one
//         compound type, turned at random on a lattice of spacing 4.5 in the
//         open box (bench/shared_pile.hpp); steps as for the pile.
// unions: N unions of four parts (an L of cubes; a capsule with a box head and
//         two spheres) on the clump pile's lattice; steps as for the cubes.
// pyramid: a pyramid of unit cubes, --n layers (20: 210 boxes); 4 000 steps (10 s).
// stack:  --n unit cubes stacked (20); 4 000 steps (10 s).
// field:  20 pyramids of --n layers (20: 4 200 boxes); 4 000 steps (10 s).
// slabs:  a tower of --n slabs 3 x 1 x 0.2 laid crosswise in pairs (100); 4 000 steps.
// column: ten spheres stacked (--n N: N spheres; a tall stack is --n 40 --ratios 1),
//         masses alternating 1 and the ratio; 2 000 steps.
// hopper: the thesis's hopper scene (examples/scene_hopper.hpp, 9 857 spheres,
//         friction 0.1 as in the scene) settled with its outlet closed: 5 000
//         steps at the library's defaults, once, then each run starts from
//         that state; 600 steps.
// Budgets: "default" is SolverSettings{} as a user gets it (tolerance, iteration
// cap and residual checks as shipped); "itK" runs exactly K iterations per step,
// the residual measured once after the last; "tolX" iterates to tolerance X
// (cap 2 000, checked every 10); "stopX" stops at tolerance X checked every 10
// iterations within the defaults' cap; "checkK" is the defaults with the residual
// checked every K iterations; "sSxK" is S substeps of exactly K iterations each
// (the substepping method; the others run S K iterations). Every run: the cone model, friction 0.5 (the
// hopper: 0.1).
// --warm: SolverSettings::warm_start (default: the library's). --backend cpu
// runs the same World on device::cpu (no GPU needed; host clock, OpenMP
// threads): its accuracy columns are the method's, its times only the host's.
// --trace N: a line every N steps (kinetic energy, iterations, residual, contacts,
// and the residual at each check with the iteration it fell after).
// --phases: World::set_phase_timing on; the medians of detection, solve and
// integration over the last third go to the ms_detection.. columns (0 without).
// --budgets: the defaults changed by one thing: itK, K iterations; tolX, the
// tolerance X; stopX, the stopping rule X (tolerance and a check every 10);
// sSxK, S substeps of K; checkK, a check every K; launched, the solve as
// launches instead of the persistent kernel; unanchored, no friction anchors;
// omegaX, the relaxation X; corrX, the share X of a penetration removed per
// step (correction). Several joined by '+' apply in turn (tol0.005+omega0.5).
// Measured, over the last third of the steps: time per whole step (detection,
// solve, integration and World's statistics, what a user's loop pays) with CUDA
// events around World::step, mean and median, from the steps before the last 200
// where there are any (those read the states back between steps, and on an H100
// their median was 9% above the others' at the 10 000-sphere pile); mean
// iterations; the median final residual. Over the last 200 steps: the largest penetration relative to the
// smaller feature size of the pair (a radius, a box's smallest half extent),
// from the contacts found every step, and from the states alone every 10 steps
// (state_penetration.hpp, `state_penetration`, as docs/piles.md measured NVIDIA
// Newton) and at the start of every step (`state_penetration_every_step`, the
// states the step's contacts were found from; `flagged_steps` counts steps where
// it and the contacts' figure differ by more than 10% of the larger and 1e-4), and
// `state_penetration_resting`, the same over pairs whose every point moves
// slower than 1 m/s (a pile's load without the bodies landing or tumbling on
// it). Over the whole run: steps at the iteration cap and diverged steps, and
// `capped_last_third`, the steps at the cap over the last third; `warm_kept`,
// the share of the last 200 steps' contacts whose pair and feature id the step
// before had (what the warm start finds). At the
// end: `drift`, the largest distance a moving body's centre moved from where
// it started, over its feature size, and `creep`, the same from where it was
// after the first quarter of the steps: a tower (pyramid, stack, field, slabs)
// "fell" where its creep reached 1% (a tall stack's drift is mostly its
// settling, every interface's penetration; before 2026-12-06 the verdict
// read the drift, and said "diverged").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../examples/scene_hopper.hpp"
#include "gpusolve/rbd/statistics/state_penetration.hpp"
#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace {
using namespace gpusolve;
using namespace gpusolve::bench;
using T = float;
using rbd::SolverSettings;

struct Options {
  std::string scene = "pile";
  std::vector<std::size_t> n;  // empty: the scene's (pile 10 000, column 10, hopper 9 857)
  std::vector<double> ratios{1, 100, 1000};
  std::vector<std::string> methods{"gauss-seidel", "jacobi"};
  std::vector<std::string> budgets{"default"};
  std::vector<double> margins{-1};  // -1: the library's default
  std::vector<double> warm{-1};     // -1: the library's default
  std::string backend = "gpu";
  std::vector<double> dts{0.0025};
  long steps = 0;  // 0: the scene's
  bool phases = false;
  long trace = 0;  // print a line every `trace` steps (0: none)
  std::string csv;
};

struct Run {
  std::string scene, method, budget;
  std::size_t n = 0;
  double ratio = 1, margin = 0, dt = 0, warm = 0;
  long steps = 0;
  bool gpu = true;
  bool phases = false;  // World::set_phase_timing: medians of each phase over the last third
  long trace = 0;
};

struct Result {
  double ms_mean = 0, ms_median = 0, penetration = 0, residual = 0, iterations = 0, kinetic = 0, height = 0, drift = 0,
         creep = 0;
  std::size_t contacts = 0, capped = 0, diverged = 0, colours = 0;
  std::size_t capped_last_third = 0;  // steps of the last third at the cap (issue 35's target: none)
  // From the states alone (state_penetration.hpp), at the end of every 10th of
  // the last 200 steps, as docs/piles.md measured NVIDIA Newton.
  double state_penetration = 0;
  // The same over pairs of resting bodies only (every point slower than
  // resting_speed): a pile's load, apart from bodies that land or tumble.
  double state_penetration_resting = 0;
  // From the states at the start of every one of the last 200 steps, the
  // states its contacts were found from: a step is flagged where the two
  // figures differ by more than 10% of the larger and by more than 1e-4 (below
  // that, both are the narrow phase's rounding: a capsule-box gap of a
  // separated pair can read -1.6e-5).
  double state_penetration_every_step = 0;
  std::size_t flagged = 0;
  double ms_detection = 0, ms_solve = 0, ms_integration = 0;  // medians; 0 without --phases
  // Over the last 200 steps: the share of contacts whose pair and feature id
  // the step before had too, so the warm start found them (a resting scene's
  // ids change only where detection flips between features).
  double warm_kept = 0;
  bool fell = false;  // a column's top sphere left its place by a radius; a tower's box moved 1% of its size
};

// Scenes that must stand still: their verdict is whether a box moved.
bool tower(const std::string& scene) {
  return scene == "pyramid" || scene == "stack" || scene == "field" || scene == "slabs";
}

// The (pair key, feature id) of each contact a step ended with, sorted.
std::vector<std::pair<std::uint64_t, std::uint32_t>> contact_ids(const rbd::RememberedContacts<T>& kept) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> ids(kept.keys.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = {kept.keys[i], kept.features[i]};
  std::sort(ids.begin(), ids.end());
  return ids;
}

// How many of `now` are in `before` (both sorted).
std::size_t kept_ids(const std::vector<std::pair<std::uint64_t, std::uint32_t>>& before,
                     const std::vector<std::pair<std::uint64_t, std::uint32_t>>& now) {
  std::size_t kept = 0;
  for (auto b = before.begin(), n = now.begin(); b != before.end() && n != now.end();)
    if (*b < *n) ++b;
    else if (*n < *b) ++n;
    else ++kept, ++b, ++n;
  return kept;
}

constexpr double hopper_friction = 0.1;  // the scene's (examples/scene_hopper.hpp)
constexpr double resting_speed = 1;      // m/s: state_penetration_resting's bound

// The fastest any point of body b moves: |v| + |w| times its bound (0 if fixed).
double point_speed(const rbd::Body<T>& b) {
  if (!rbd::moves(b.status)) return 0;
  const auto norm = [](const std::array<T, 3>& x) { return std::sqrt(double(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])); };
  const auto& p = b.shape_param;
  return norm(b.v) + norm(b.w) * double(rbd::shape_bound<T>(b.shape, p[0], p[1], p[2]));
}

// One change of a budget (see --budgets) applied to s.
void apply_budget(const std::string& b, SolverSettings<T>& s) {
  if (b.rfind("it", 0) == 0) {
    s.max_iterations = std::stoul(b.substr(2));
    s.check_every = s.max_iterations;
    s.tolerance = std::numeric_limits<T>::min();
  } else if (b.rfind("tol", 0) == 0) {
    s.tolerance = T(std::stod(b.substr(3)));
    s.max_iterations = 2000;
    s.check_every = 10;
  } else if (b.rfind("s", 0) == 0 && b.find('x') != std::string::npos) {
    s.substeps = std::stoul(b.substr(1));
    s.max_iterations = s.substeps * std::stoul(b.substr(b.find('x') + 1));
    s.check_every = s.max_iterations;
    s.tolerance = std::numeric_limits<T>::min();
  } else if (b.rfind("check", 0) == 0) {
    s.check_every = std::stoul(b.substr(5));
  } else if (b.rfind("stop", 0) == 0) {
    s.tolerance = T(std::stod(b.substr(4)));  // a stopping rule within the defaults' cap
    s.check_every = 10;
  } else if (b.rfind("omega", 0) == 0) {
    s.omega = T(std::stod(b.substr(5)));  // the relaxation (0: the method's default)
  } else if (b.rfind("corr", 0) == 0) {
    s.correction = T(std::stod(b.substr(4)));  // the defaults with another share of a penetration removed per step
  } else if (b == "launched") {
    s.persistent_max_contacts = 0;  // the defaults, as launches instead of the persistent kernel
  } else if (b == "unanchored") {
    s.friction_anchors = false;  // the defaults without friction anchors
  } else if (b != "default") {
    throw InvalidArgumentError("atlas: unknown budget '" + b +
                               "' (default, itK, sSxK, tolX, stopX, checkK, omegaX, corrX, launched or unanchored, joined by +)");
  }
}

SolverSettings<T> settings_for(const Run& r) {
  SolverSettings<T> s;
  s.dt = T(r.dt);
  s.friction = T(r.scene == "hopper" ? hopper_friction : 0.5);
  if (r.margin >= 0) s.margin = T(r.margin);
  s.warm_start = T(r.warm);
  // A budget is one change of the defaults or several joined by '+' (tol0.005+omega0.5).
  for (std::size_t from = 0; from <= r.budget.size();) {
    const std::size_t to = std::min(r.budget.find('+', from), r.budget.size());
    apply_budget(r.budget.substr(from, to - from), s);
    from = to + 1;
  }
  return s;
}

// The hopper of n spheres after its warm-up with the outlet closed, built and settled once.
template <class Dev>
const rbd::BodySet<T>& settled_hopper(std::size_t n) {
  static std::size_t built = 0;
  static rbd::BodySet<T> set;
  if (built == n) return set;
  scenes::Options o;
  o.scene = "hopper";
  o.scale = long(n);
  o.resolve(scenes::Hopper<T>::defaults());
  scenes::Hopper<T> hopper(o);
  set = rbd::BodySet<T>();
  hopper.build(set);
  SolverSettings<T> s;
  s.friction = T(hopper_friction);
  rbd::World<Dev, T> world(set, s);
  std::printf("... hopper n=%zu: settling %ld steps at the defaults, outlet closed\n", n, hopper.warmup());
  std::fflush(stdout);
  world.advance(std::size_t(hopper.warmup()));
  const rbd::StepStats<T> st = world.latest_stats();
  world.syncHost();
  std::printf("    %zu contacts, penetration %.4f%%\n", st.solver.contacts, 100 * double(st.max_penetration));
  built = n;
  return set;
}

template <class Dev>
rbd::BodySet<T> scene_set(const Run& r) {
  if (r.scene == "pile") return shared_pile<T>(r.n);
  if (r.scene == "cubes") return cube_pile<T>(r.n);
  if (r.scene == "mixed") return mixed_pile<T>(r.n);
  if (r.scene == "clumps") return clump_pile<T>(r.n);
  if (r.scene == "unions") return union_pile<T>(r.n);
  if (r.scene == "pyramid") return box_pyramid<T>(r.n);
  if (r.scene == "stack") return box_stack<T>(r.n);
  if (r.scene == "field") return pyramid_field<T>(r.n);
  if (r.scene == "slabs") return slab_tower<T>(r.n);
  if (r.scene == "column") return mass_column<T>(r.n, r.ratio);
  return settled_hopper<Dev>(r.n);
}

// Milliseconds of one step: CUDA events on the GPU, the host clock on the CPU
// backend (which runs as it queues).
template <class Dev>
class StepTimer;
template <>
class StepTimer<device::gpu> : public EventTimer {
 public:
  StepTimer() : EventTimer(stream_t{}) {}
};
template <>
class StepTimer<device::cpu> {
 public:
  void start() { t0_ = std::chrono::steady_clock::now(); }
  double stop_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

template <class Dev, class Method>
Result run(const Run& r) {
  rbd::BodySet<T> set = scene_set<Dev>(r);
  const rbd::BodySet<T> start = set;
  rbd::BodySet<T> settled = set;  // after the first quarter of the steps
  const SolverSettings<T> s = settings_for(r);
  rbd::World<Dev, T, rbd::ConeFriction, Method> world(set, s);
  world.set_phase_timing(r.phases);
  StepTimer<Dev> timer;
  std::vector<double> ms, residuals, detection, solve, integration;
  Result out;
  double iterations = 0;
  const long last_third = r.steps - r.steps / 3;
  const long timed_end = r.steps - 200 > last_third ? r.steps - 200 : r.steps;  // see "Measured" above
  std::vector<std::pair<std::uint64_t, std::uint32_t>> ids;  // the step before's contacts
  std::size_t kept = 0, compared = 0;
  bool host_current = false;  // `set` holds the states the next step starts from
  for (long step = 0; step < r.steps; ++step) {
    const bool measured = step >= r.steps - 200;
    double at_start = 0;  // the deepest overlap from the states the step starts from
    if (measured) {
      if (!host_current) world.syncHost();
      at_start = rbd::state_penetration(set).relative;
    }
    timer.start();
    const rbd::StepStats<T> st = world.step();
    host_current = false;
    const double t = timer.stop_ms();
    out.capped += st.solver.status == rbd::SolverStatus::max_iterations;
    if (r.trace > 0 && step % r.trace == 0) {
      std::printf("    step %ld: kinetic energy %.4g, %zu iterations, residual %.3g, %zu contacts, checks", step,
                  double(st.kinetic_energy), st.solver.iterations, double(st.solver.residual()), st.solver.contacts);
      for (std::size_t k = 0; k < st.solver.residuals.size(); ++k)
        std::printf(" %zu:%.3g", st.solver.checked_at[k], double(st.solver.residuals[k]));
      std::printf("\n");
    }
    out.diverged += st.solver.status == rbd::SolverStatus::diverged || !std::isfinite(st.max_penetration);
    if (step >= last_third && step < timed_end) {
      ms.push_back(t);
      detection.push_back(1e3 * st.time_detection);
      solve.push_back(1e3 * st.time_solve);
      integration.push_back(1e3 * st.time_integration);
    }
    if (step >= last_third) {
      residuals.push_back(double(st.solver.residual()));
      iterations += double(st.solver.total_iterations);
      out.capped_last_third += st.solver.status == rbd::SolverStatus::max_iterations;
    }
    if (measured) {
      const double found = double(st.max_penetration);
      out.penetration = std::max(out.penetration, found);
      out.state_penetration_every_step = std::max(out.state_penetration_every_step, at_start);
      const double larger = std::max(at_start, found), apart = std::fabs(at_start - found);
      out.flagged += apart > 0.1 * larger && apart > 1e-4;
      auto now = contact_ids(world.remembered_contacts());
      if (step > r.steps - 200) kept += kept_ids(ids, now), compared += now.size();
      ids = std::move(now);
    }
    if (measured && (r.steps - 1 - step) % 10 == 0) {
      world.syncHost();
      host_current = true;
      double from_states = 0, resting = 0;  // every pair's, and resting pairs' (one pass)
      rbd::for_each_state_overlap(set, [&](std::size_t a, std::size_t b, double relative) {
        from_states = std::max(from_states, relative);
        if (point_speed(set[a]) < resting_speed && point_speed(set[b]) < resting_speed)
          resting = std::max(resting, relative);
      });
      out.state_penetration = std::max(out.state_penetration, from_states);
      out.state_penetration_resting = std::max(out.state_penetration_resting, resting);
    }
    if (step + 1 == r.steps / 4) {
      world.syncHost();
      host_current = true;
      settled = set;
    }
    if (step + 1 == r.steps) {
      out.contacts = st.solver.contacts;
      out.kinetic = st.kinetic_energy;
      out.colours = st.solver.colours;
    }
  }
  out.warm_kept = compared == 0 ? 1 : double(kept) / double(compared);
  world.syncHost();
  for (std::size_t i = 0; i < set.size(); ++i)
    if (set[i].status == rbd::active) {
      out.height = std::max(out.height, double(set[i].pos[2]));
      const auto& p = set[i].shape_param;
      const double size = set[i].shape == rbd::compound ? double(p[2])  // its smallest feature
                                                        : double(rbd::shape_feature_size<T>(set[i].shape, p[0], p[1], p[2]));
      const auto moved = [&](const rbd::BodySet<T>& from) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += std::pow(double(set[i].pos[c]) - double(from[i].pos[c]), 2);
        return std::sqrt(d2) / size;
      };
      out.drift = std::max(out.drift, moved(start));
      out.creep = std::max(out.creep, moved(settled));
    }
  if (r.scene == "column") out.fell = std::fabs(out.height - double(2 * r.n - 1)) > 1.0;
  if (tower(r.scene)) out.fell = out.creep > 0.01;  // a box moved 1% of its size once settled
  double sum = 0;
  for (double v : ms) sum += v;
  out.ms_mean = sum / double(ms.size());
  out.ms_median = spread(ms).median;
  out.residual = spread(residuals).median;
  out.ms_detection = spread(detection).median;
  out.ms_solve = spread(solve).median;
  out.ms_integration = spread(integration).median;
  out.iterations = iterations / double(residuals.size());
  return out;
}

template <class Dev>
Result dispatch(const Run& r) {
  if (r.method == "gauss-seidel") return run<Dev, rbd::ColouredGaussSeidel>(r);
  if (r.method == "jacobi") return run<Dev, rbd::Jacobi<rbd::Gather>>(r);
  if (r.method == "apgd") return run<Dev, rbd::AcceleratedJacobi<rbd::Gather>>(r);
  if (r.method == "substepping") return run<Dev, rbd::Substepping<>>(r);
  if (r.method == "apgd-cg") return run<Dev, rbd::AcceleratedCG>(r);
  throw InvalidArgumentError("atlas: unknown method '" + r.method +
                             "' (gauss-seidel, jacobi, apgd, substepping or apgd-cg)");
}

const char* verdict(const Run& r, const Result& x) {
  if (x.diverged > 0 || !(x.penetration < 0.5)) return "diverged";
  if (x.fell) return "fell";
  return x.capped > std::size_t(r.steps / 100) ? "capped" : "converged";
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const char* usage =
      "--scene pile|cubes|mixed|clumps|unions|column|pyramid|stack|field|slabs|hopper [--n LIST] [--ratios LIST] [--methods LIST] [--budgets LIST] [--margins LIST] "
      "[--warm LIST] [--dts LIST] [--steps N] [--backend gpu|cpu] [--phases] [--trace N] [--csv FILE]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--scene") o.scene = option_value(argc, argv, i);
    else if (a == "--n") o.n = parse_list<std::size_t>(option_value(argc, argv, i));
    else if (a == "--ratios") o.ratios = parse_list<double>(option_value(argc, argv, i));
    else if (a == "--methods") o.methods = parse_words(option_value(argc, argv, i));
    else if (a == "--budgets") o.budgets = parse_words(option_value(argc, argv, i));
    else if (a == "--margins") o.margins = parse_list<double>(option_value(argc, argv, i));
    else if (a == "--warm") o.warm = parse_list<double>(option_value(argc, argv, i));
    else if (a == "--backend") o.backend = option_value(argc, argv, i);
    else if (a == "--dts") o.dts = parse_list<double>(option_value(argc, argv, i));
    else if (a == "--steps") o.steps = std::stol(option_value(argc, argv, i));
    else if (a == "--phases") o.phases = true;
    else if (a == "--trace") o.trace = std::stol(option_value(argc, argv, i));
    else if (a == "--csv") o.csv = option_value(argc, argv, i);
    else usage_exit(argv[0], usage, a);
  }
  const std::vector<std::string> scenes{"pile", "cubes", "mixed", "clumps", "unions", "column", "pyramid", "stack", "field", "slabs", "hopper"};
  if (std::find(scenes.begin(), scenes.end(), o.scene) == scenes.end()) usage_exit(argv[0], usage, "--scene " + o.scene);
  if (o.backend != "gpu" && o.backend != "cpu") usage_exit(argv[0], usage, "--backend " + o.backend);
  try {
    const char* what = "gpusolve atlas: whole World steps, time per step against accuracy";
    std::string gpu;
    if (o.backend == "gpu") {
      gpu = print_banner(what);
    } else {
#if defined(_OPENMP)
      const int threads = omp_get_max_threads();
#else
      const int threads = 1;
#endif
      gpu = "cpu backend (" + std::to_string(threads) + " threads)";
      std::printf("%s\n%s: times are the host's\n", what, gpu.c_str());
    }
    std::FILE* csv = open_csv(
        o.csv,
        "scene,n,mass_ratio,method,budget,margin,warm_start,dt,steps,ms_per_step_mean,ms_per_step_median,contacts,colours,"
        "max_penetration,residual_median,iterations_mean,capped_steps,diverged_steps,kinetic_energy,height,drift,verdict,"
        "state_penetration,flagged_steps,ms_detection,ms_solve,ms_integration,gpu,creep,state_penetration_resting,"
        "state_penetration_every_step,capped_last_third,warm_kept");
    const std::vector<double> ratios = o.scene == "column" ? o.ratios : std::vector<double>{1};
    const bool is_tower = tower(o.scene);
    const std::size_t scene_n = o.scene == "column"   ? 10
                                : o.scene == "hopper" ? 9857
                                : o.scene == "slabs"  ? 100
                                : is_tower            ? 20
                                                      : 10000;
    const std::vector<std::size_t> ns = !o.n.empty() ? o.n : std::vector<std::size_t>{scene_n};
    for (std::size_t n : ns)
      for (double ratio : ratios)
        for (double dt : o.dts)
          for (double margin : o.margins)
            for (double warm : o.warm)
            for (const auto& method : o.methods)
              for (const auto& budget : o.budgets) {
                Run r{o.scene, method, budget, n, ratio, margin, dt, warm, o.steps, o.backend == "gpu", o.phases, o.trace};
                if (r.steps == 0)
                  r.steps = o.scene == "column"                        ? 2000
                            : o.scene == "hopper"                      ? 600
                            : is_tower                                 ? 4000
                            : o.scene == "cubes" || o.scene == "mixed" || o.scene == "unions" ? 2400
                            : n <= 10000                               ? 1200
                                                                       : 900;
                if (r.margin < 0) r.margin = double(SolverSettings<T>{}.margin);
                if (r.warm < 0) r.warm = double(SolverSettings<T>{}.warm_start);
                std::printf("... %s n=%zu ratio=%g %s %s margin=%g warm %g dt=%g, %ld steps\n", r.scene.c_str(), n,
                            ratio, method.c_str(), budget.c_str(), r.margin, r.warm, dt, r.steps);
                std::fflush(stdout);
                const Result x = r.gpu ? dispatch<device::gpu>(r) : dispatch<device::cpu>(r);
                std::printf("    %.3f ms/step (median %.3f), penetration %.4f%% (states %.4f%%, every step %.4f%%, resting pairs %.4f%%, "
                            "%zu flagged), "
                            "residual %.3g, %.1f iterations, %zu contacts, %zu colours, capped %zu (last third %zu), diverged %zu, "
                            "drift %.4f, creep %.4f, %.2f%% of contacts kept: %s\n",
                            x.ms_mean, x.ms_median, 100 * x.penetration, 100 * x.state_penetration,
                            100 * x.state_penetration_every_step, 100 * x.state_penetration_resting, x.flagged,
                            x.residual, x.iterations, x.contacts, x.colours, x.capped, x.capped_last_third, x.diverged,
                            x.drift, x.creep, 100 * x.warm_kept, verdict(r, x));
                if (r.phases)
                  std::printf("    phases (medians): detection %.3f ms, solve %.3f ms, integration %.3f ms\n",
                              x.ms_detection, x.ms_solve, x.ms_integration);
                std::fflush(stdout);
                if (csv)
                  std::fprintf(csv, "%s,%zu,%g,%s,%s,%g,%g,%g,%ld,%.4f,%.4f,%zu,%zu,%.6g,%.4g,%.2f,%zu,%zu,%.6g,%.4f,%.5f,%s,%.6g,%zu,%.4f,%.4f,%.4f,%s,%.6f,%.6g,%.6g,%zu,%.5f\n",
                               r.scene.c_str(), n, ratio, method.c_str(), budget.c_str(), r.margin, r.warm, dt, r.steps,
                               x.ms_mean, x.ms_median, x.contacts, x.colours, x.penetration, x.residual, x.iterations,
                               x.capped, x.diverged, x.kinetic, x.height, x.drift, verdict(r, x), x.state_penetration,
                               x.flagged, x.ms_detection, x.ms_solve, x.ms_integration, gpu.c_str(), x.creep,
                               x.state_penetration_resting, x.state_penetration_every_step, x.capped_last_third,
                               x.warm_kept);
              }
    if (csv) std::fclose(csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpusolve_bench_atlas: %s\n", e.what());
    return 1;
  }
  return 0;
}
