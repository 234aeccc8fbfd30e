// The whole time step, per phase and in total, on the GPU and the CPU backend.
//
// Run: gpusolve_bench_step [--n 1000,10000,100000,1000000] [--modes jacobi10,defaults,tolerance,check50,rolling]
//                          [--loop auto,auto-grid,auto-nograph,persistent,launches,graphs] [--settle 900] [--steps 100] [--cpu-steps 20]
//                          [--cpu-max 1000000] [--one-world] [--reorder N] [--scene pile|cubes] [--csv FILE]
//
// For each N the shared pile (bench/shared_pile.hpp, docs/piles.md; --scene cubes: the cube pile)
// falls for `settle` steps on the GPU at the library's defaults; every timing
// then starts from that same settled state, copied into a fresh World:
//   jacobi10:  projected Jacobi (gather), exactly 10 iterations per step, one check;
//   atomic10:  the same with atomic accumulation (one phase per iteration);
//   defaults:  World<device::gpu> with SolverSettings{} (APGD, 50 iterations);
//   tolerance: APGD to the default tolerance 5e-3, checked every 10, at most 500;
//   check50:   the defaults with one residual check, after the 50th iteration (the
//              defaults until 2026-12-07): what the defaults' checks cost;
//   rolling:   the defaults with the six-row contact model (ConeRollingFriction), rolling
//              and spinning resistance 0.01 (a hundredth of the radius): the cost of
//              the angular rows against `defaults` (issue 37).
// --loop: how the GPU runs the solver's iterations between two residual checks:
//   auto         the library's choice (SolverSettings::persistent_max_contacts,
//                detection as a kept CUDA graph: detection_graph, and a persistent
//                kernel of at most 16 blocks as one cluster: persistent_clusters);
//   auto-grid    the same with every persistent kernel launched cooperatively;
//   auto-nograph the same with detection launched kernel by kernel;
//   persistent   one cooperative kernel at any size;
//   launches     a kernel launch per phase, detection too (persistent_max_contacts 0,
//                graphs and detection_graph off);
//   graphs       the solver's launches captured into CUDA graphs
//                (persistent_max_contacts 0, graphs on).
// GPU, after 20 warm-up steps:
//   step     median of CUDA-event times around each advance(1): what a step loop pays;
//   queued   advance(steps) timed as one: steps queued back to back, divided by steps;
//   unattended  advance_unattended(steps) and finish() timed as one, divided by
//            steps: no host wait at all (the contact count stays on the device);
//            the steps it had to queue again (a contact list that grew) are
//            printed, and their second run is in the time;
//            queued and unattended each run in a World of their own from the
//            same state, after the same warm-up: the same steps; the mean
//            iterations of the unattended steps come from one more World that
//            takes them unattended one by one, reading each step's statistics;
//   phases   medians of the World's per-phase event times (set_phase_timing) over
//            as many more steps.
// --one-world: for sizes where two Worlds do not fit the GPU (100M spheres on an
//   H200): only `step` and `phases`, each mode in one World built from the
//   settled state with none beside it (no queued, unattended or counted World,
//   no copies of the state for them); queued and unattended print 0, the CPU
//   backend is skipped.
// --reorder N: every World puts its bodies in spatial order every N steps
//   (ExecutionSettings::reorder_every): the settling World, and each timed one,
//   which starts again from the BodySet's order and reorders first at its
//   N-th step (within the 20 warm-up steps for N <= 20).
// Also printed, and in the CSV: the solve's contact-iterations per second (contacts times
// iterations over the solve phase's time).
// CPU backend: the same World on device::cpu from the same state (host clock;
// its kernels run as OpenMP loops where the build has OpenMP, the thread count
// is printed), after 2 warm-up steps; sizes above --cpu-max are skipped.
// Also printed: contacts, iterations, the largest penetration over the timed
// steps and the median residual: the accuracy the time bought; and the GPU
// memory the stepping World's buffers hold after its timed steps, in all and
// per body (memory::memory_use; 0 on the CPU backend).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

namespace {

using namespace gpusolve;
using namespace gpusolve::bench;
using rbd::SolverSettings;
using T = float;

struct Options {
  std::vector<std::size_t> n{1000, 10000, 100000, 1000000};
  std::vector<std::string> modes{"jacobi10", "defaults", "tolerance"};
  std::vector<std::string> loops{"auto"};
  long settle = 900, steps = 100, cpu_steps = 20;
  std::size_t cpu_max = 1000000;
  bool one_world = false;
  std::size_t reorder = 0;
  std::string scene = "pile";  // or "cubes"
  std::string csv;
};

struct Row {
  double step_ms = 0, queued_ms = 0, unattended_ms = 0, detection_ms = 0, solve_ms = 0, integration_ms = 0;
  double iterations = 0, penetration = 0, residual = 0, unattended_iterations = 0;
  std::size_t contacts = 0, steps = 0, requeued = 0;
  std::size_t device_bytes = 0;  // GPU memory the stepping World's buffers hold (0 on the CPU backend)
};

SolverSettings<T> settings_for(const std::string& mode, const std::string& loop) {
  SolverSettings<T> s;
  if (loop == "persistent")
    s.persistent_max_contacts = ~std::size_t(0);
  else if (loop == "launches" || loop == "graphs")
    s.persistent_max_contacts = 0;
  else if (loop != "auto" && loop != "auto-grid" && loop != "auto-nograph")
    throw InvalidArgumentError("bench: unknown loop '" + loop +
                               "' (auto, auto-grid, auto-nograph, persistent, launches, graphs)");
  s.persistent_clusters = loop != "auto-grid";
  s.graphs = loop == "graphs";
  s.detection_graph = loop != "auto-nograph" && loop != "launches";
  s.friction = T(0.5);  // docs/piles.md
  if (mode == "jacobi10" || mode == "atomic10") {
    s.max_iterations = 10, s.check_every = 10;
    s.tolerance = T(1e-30);  // runs all 10
  } else if (mode == "tolerance") {
    s.max_iterations = 500, s.check_every = 10;
  } else if (mode == "check50") {
    s.check_every = 50;
  } else if (mode == "rolling") {
    s.rolling = T(0.01), s.spinning = T(0.01);
  } else if (mode != "defaults") {
    throw InvalidArgumentError("bench: unknown mode '" + mode + "' (jacobi10, atomic10, defaults, tolerance, check50, rolling)");
  }
  return s;
}

// What the timed steps of one backend and mode leave: their times and figures.
struct Samples {
  std::vector<double> ms, residuals, detection, solve, integration;
  Row row;
  void accuracy(const rbd::StepStats<T>& st) {
    row.iterations += double(st.solver.total_iterations);
    row.penetration = std::max(row.penetration, double(st.max_penetration));
    residuals.push_back(double(st.solver.residual()));
    row.contacts = st.solver.contacts;
  }
  void phases(const rbd::StepStats<T>& st) {
    detection.push_back(1e3 * st.time_detection);
    solve.push_back(1e3 * st.time_solve);
    integration.push_back(1e3 * st.time_integration);
  }
  Row medians(long steps) {
    row.step_ms = spread(ms).median;
    row.detection_ms = spread(detection).median, row.solve_ms = spread(solve).median;
    row.integration_ms = spread(integration).median;
    row.iterations /= double(steps);
    row.residual = spread(residuals).median;
    row.steps = std::size_t(steps);
    return row;
  }
};

// Times `world`'s steps one by one after 20 warm-up steps, then its phases.
template <class World>
Row time_world(World& world, long steps) {
  world.advance(20);
  EventTimer timer(stream_t{});
  Samples x;
  for (long k = 0; k < steps; ++k) {
    timer.start();
    world.advance(1);
    x.ms.push_back(timer.stop_ms());
    x.accuracy(world.latest_stats());
  }
  x.row.device_bytes = memory::memory_use<memory::device>().now;  // only this World is alive
  world.set_phase_timing(true);
  for (long k = 0; k < steps; ++k) {
    world.advance(1);
    x.phases(world.latest_stats());
  }
  world.set_phase_timing(false);
  return x.medians(steps);
}

template <class Method, class Model>
Row time_gpu(const rbd::BodySet<T>& start, const SolverSettings<T>& s, long steps, bool one_world) {
  using World = rbd::World<device::gpu, T, Model, Method>;
  Row row;
  {
    rbd::BodySet<T> set = start;
    World world(set, s);
    row = time_world(world, steps);
  }
  if (one_world) return row;
  rbd::BodySet<T> queued_set = start, unattended_set = start, counted_set = start;
  EventTimer timer(stream_t{});
  {
    World queued(queued_set, s);
    queued.advance(20);
    timer.start();
    queued.advance(std::size_t(steps));
    row.queued_ms = timer.stop_ms() / double(steps);
  }
  {
    World unattended(unattended_set, s);
    unattended.advance(20);
    timer.start();
    unattended.advance_unattended(std::size_t(steps));
    unattended.finish();  // takes held steps again: they cost their time too
    row.unattended_ms = timer.stop_ms() / double(steps);
    row.requeued = unattended.steps_requeued();
  }
  {
    World counted(counted_set, s);
    counted.advance(20);
    for (long k = 0; k < steps; ++k) {
      counted.advance_unattended(1);
      row.unattended_iterations += double(counted.latest_stats().solver.total_iterations) / double(steps);
    }
  }
  return row;
}

template <class Method, class Model>
Row time_cpu(rbd::BodySet<T> set, const SolverSettings<T>& s, long steps) {
  rbd::World<device::cpu, T, Model, Method> world(set, s);
  world.advance(2);
  world.set_phase_timing(true);
  Samples x;
  for (long k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    world.advance(1);
    x.ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    const auto st = world.latest_stats();
    x.accuracy(st);
    x.phases(st);
  }
  Row r = x.medians(steps);
  r.queued_ms = r.unattended_ms = r.step_ms;  // the host backend runs as it queues
  r.unattended_iterations = r.iterations;
  return r;
}

template <class Method, class Model = rbd::ConeFriction>
Row time_backend(bool gpu, const rbd::BodySet<T>& set, const SolverSettings<T>& s, long steps, bool one_world) {
  return gpu ? time_gpu<Method, Model>(set, s, steps, one_world) : time_cpu<Method, Model>(set, s, steps);
}

Row time_mode(bool gpu, const std::string& mode, const std::string& loop, const rbd::BodySet<T>& set, long steps,
              bool one_world, std::size_t reorder) {
  SolverSettings<T> s = settings_for(mode, loop);
  s.reorder_every = reorder;
  if (mode == "jacobi10") return time_backend<rbd::Jacobi<rbd::Gather>>(gpu, set, s, steps, one_world);
  if (mode == "atomic10") return time_backend<rbd::Jacobi<rbd::Atomic>>(gpu, set, s, steps, one_world);
  if (mode == "rolling")
    return time_backend<rbd::AcceleratedJacobi<rbd::Gather>, rbd::ConeRollingFriction>(gpu, set, s, steps,
                                                                                       one_world);
  return time_backend<rbd::AcceleratedJacobi<rbd::Gather>>(gpu, set, s, steps, one_world);
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  const char* usage =
      "[--n LIST] [--modes jacobi10,defaults,tolerance,check50,rolling] [--loop auto,auto-grid,auto-nograph,persistent,launches,graphs] [--settle N] [--steps N] [--cpu-steps N] [--cpu-max N] "
      "[--one-world] [--reorder N] [--scene pile|cubes] [--csv FILE]";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--n") o.n = parse_list<std::size_t>(option_value(argc, argv, i));
    else if (a == "--modes") o.modes = parse_words(option_value(argc, argv, i));
    else if (a == "--loop") o.loops = parse_words(option_value(argc, argv, i));
    else if (a == "--settle") o.settle = std::stol(option_value(argc, argv, i));
    else if (a == "--steps") o.steps = std::max(1L, std::stol(option_value(argc, argv, i)));
    else if (a == "--cpu-steps") o.cpu_steps = std::max(1L, std::stol(option_value(argc, argv, i)));
    else if (a == "--cpu-max") o.cpu_max = std::stoul(option_value(argc, argv, i));
    else if (a == "--one-world") o.one_world = true;
    else if (a == "--reorder") o.reorder = std::stoul(option_value(argc, argv, i));
    else if (a == "--scene") o.scene = option_value(argc, argv, i);
    else if (a == "--csv") o.csv = option_value(argc, argv, i);
    else usage_exit(argv[0], usage, a);
  }
  if (o.scene != "pile" && o.scene != "cubes") usage_exit(argv[0], usage, "--scene " + o.scene);
  try {
    const std::string gpu_name = print_banner("gpusolve whole-step benchmark: the shared pile, per phase and in total");
#if defined(_OPENMP)
    const int cpu_threads = omp_get_max_threads();
#else
    const int cpu_threads = 1;
#endif
    std::printf("CPU backend: %d thread(s)\n", cpu_threads);
    std::FILE* csv = open_csv(o.csv,
                              "backend,n,mode,loop,contacts,steps,ms_step_median,ms_step_queued,ms_detection,ms_solve,"
                              "ms_integration,iterations_mean,max_penetration,residual_median,cpu_threads,gpu,"
                              "ms_step_unattended,steps_requeued,iterations_mean_unattended,device_bytes,"
                              "device_bytes_per_body,reorder_every,g_contact_iterations_per_s,scene");
    for (std::size_t n : o.n) {
      rbd::BodySet<T> set = o.scene == "cubes" ? cube_pile<T>(n) : shared_pile<T>(n);
      {
        std::printf("... n=%zu: settling %ld steps on the GPU at the defaults\n", n, o.settle);
        std::fflush(stdout);
        SolverSettings<T> s;
        s.friction = T(0.5);
        s.reorder_every = o.reorder;
        rbd::World<device::gpu, T> settle(set, s);
        settle.advance(std::size_t(o.settle));
        settle.syncHost();
        std::printf("    %zu contacts, penetration %.4f%%\n", settle.latest_stats().solver.contacts,
                    100 * double(settle.latest_stats().max_penetration));
      }
      for (const bool gpu : {true, false}) {
        if (!gpu && (n > o.cpu_max || o.one_world)) continue;
        for (const auto& mode : o.modes)
          for (const auto& g : o.loops) {
            if (!gpu && &g != &o.loops.front()) continue;  // the CPU backend has one loop: one row
            const long steps = gpu ? o.steps : o.cpu_steps;
            std::printf("... %s n=%zu %s loop %s, %ld steps\n", gpu ? "gpu" : "cpu", n, mode.c_str(),
                        gpu ? g.c_str() : "-", steps);
            std::fflush(stdout);
            const Row r = time_mode(gpu, mode, g, set, steps, o.one_world, o.reorder);
            std::printf("    %s %s %s: %zu contacts: step %.3f ms (queued %.3f ms, unattended %.3f ms, %zu steps "
                        "requeued), detection %.3f, solve %.3f, integration %.3f ms; %.1f iterations (unattended "
                        "%.1f), penetration %.4f%%, residual %.3g; %.0f bytes of GPU memory per body\n",
                        gpu ? "gpu" : "cpu", mode.c_str(), gpu ? g.c_str() : "-", r.contacts, r.step_ms, r.queued_ms,
                        r.unattended_ms, r.requeued, r.detection_ms, r.solve_ms, r.integration_ms, r.iterations,
                        r.unattended_iterations, 100 * r.penetration, r.residual, double(r.device_bytes) / double(n));
            const double rate = r.solve_ms > 0 ? double(r.contacts) * r.iterations / (r.solve_ms * 1e6) : 0.0;
            if (rate > 0) std::printf("    solve: %.2f G contact-iterations per second\n", rate);
            std::fflush(stdout);
            if (csv)
              std::fprintf(csv, "%s,%zu,%s,%s,%zu,%zu,%.5f,%.5f,%.5f,%.5f,%.5f,%.2f,%.6g,%.4g,%d,%s,%.5f,%zu,%.2f,%zu,%.1f,%zu,%.3f,%s\n",
                           gpu ? "gpu" : "cpu", n, mode.c_str(), gpu ? g.c_str() : "-", r.contacts, r.steps, r.step_ms,
                           r.queued_ms, r.detection_ms, r.solve_ms, r.integration_ms, r.iterations, r.penetration,
                           r.residual, cpu_threads, gpu_name.c_str(), r.unattended_ms, r.requeued,
                           r.unattended_iterations, r.device_bytes, double(r.device_bytes) / double(n), o.reorder,
                           rate, o.scene.c_str());
          }
      }
    }
    if (csv) std::fclose(csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpusolve_bench_step: %s\n", e.what());
    return 1;
  }
  return 0;
}
