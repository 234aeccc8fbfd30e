// Speed against accuracy of one time step's contact solve: LCP residual after k
// iterations, and the wall time of a solve that stops after k iterations, for
// the GPU Jacobi solver at several omegas, the CPU backend of the same Jacobi
// code, and the host Gauss-Seidel reference.
//
// Run: gpusolve_bench_accuracy [--contacts 20000] [--omegas 0.2,0.35,0.5,0.7,1.0] [--max-iters 2000]
//                              [--repeats 5] [--cpu-repeats 1] [--cpu-omega 0.5] [--gs-omega 1.0]
//                              [--model pyramid|frictionless] [--csv FILE]
// Plot: python3 tools/plot_bench.py FILE.csv -o accuracy.png
//
// Each point is one solve with max_iterations = k and check_every = k (one
// residual check, at the end, as a user who asks for k iterations pays), started
// from the same velocities, its wall time the median of the repeats: CUDA events
// for the GPU, a steady clock for the host. k runs over a 1-2-3-5-7 ladder up to
// --max-iters. The residual is the solver's own (contact_kernels.hpp). A solve
// that diverges stops early; its row says how many iterations it ran.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "gpusolve/rbd/solvers/pgs.hpp"
#include "pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using namespace gpusolve::bench;
using T = float;

struct Options {
  std::size_t contacts = 20000, max_iters = 2000;
  std::vector<double> omegas{0.2, 0.35, 0.5, 0.7, 1.0};
  int repeats = 5, cpu_repeats = 1;
  double cpu_omega = 0.5, gs_omega = 1.0;
  std::string model = "pyramid", csv;
};

std::vector<std::size_t> ladder(std::size_t max) {
  std::vector<std::size_t> out;
  for (std::size_t decade = 1; decade <= max; decade *= 10)
    for (std::size_t m : {1, 2, 3, 5, 7})
      if (m * decade <= max) out.push_back(m * decade);
  if (out.back() != max) out.push_back(max);
  return out;
}

// One curve: (iterations, seconds, residual) per ladder rung.
struct Point {
  std::size_t asked, ran;
  Spread seconds;
  double residual;
};

// solve(settings) returns SolverStats and runs on its own data; seconds() times one call.
template <class Solve>
std::vector<Point> curve(const Options& opt, double omega, int repeats, Solve&& solve) {
  std::vector<Point> out;
  for (std::size_t k : ladder(opt.max_iters)) {
    rbd::SolverSettings<T> s;
    s.omega = T(omega);
    s.tolerance = std::numeric_limits<T>::denorm_min();  // run all k iterations
    s.divergence_checks = 0;                              // only NaN/inf stops a solve
    s.max_retries = 0;  // time the iterations, not restarts at a lower omega
    s.max_iterations = k;
    s.check_every = k;
    std::vector<double> secs;
    rbd::SolverStats<T> st;
    for (int r = 0; r < repeats; ++r) secs.push_back(solve(s, st));
    out.push_back({k, st.iterations, spread(secs), double(st.residual())});
    if (st.status == rbd::SolverStatus::diverged) break;
  }
  return out;
}

void emit(std::FILE* csv, const std::string& gpu, const char* solver, const char* backend, double omega,
          std::size_t nc, const std::vector<Point>& pts) {
  std::printf("%-13s %-10s omega %.2f:", solver, backend, omega);
  for (const Point& p : pts)
    if (p.asked == 10 || p.asked == 100 || p.asked == 1000 || &p == &pts.back())
      std::printf("  k=%zu %.3g m/s in %.3g ms", p.ran, p.residual, p.seconds.median * 1e3);
  std::printf("\n");
  if (csv)
    for (const Point& p : pts)
      std::fprintf(csv, "\"%s\",%s,%s,%.3f,%zu,%zu,%zu,%.6e,%.6e,%.6e,%.6e\n", gpu.c_str(), solver, backend, omega, nc,
                   p.asked, p.ran, p.seconds.median, p.seconds.min, p.seconds.max, p.residual);
}

template <class Model>
void run(rbd::BodySet<T>& set, const Options& opt, std::FILE* csv, const std::string& gpu) {
  using Host = device::cpu;
  using Dev = device::gpu;
  cudaStream_t stream;
  GPUSOLVE_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  const T mu = rbd::SolverSettings<T>{}.friction;

  rbd::BodyManager<Dev, T> gpu_manager(set);
  gpu_manager.syncDeviceFull(stream);
  auto& gb = gpu_manager.device();
  rbd::Contacts<Dev, T, Model> gc;
  rbd::CollisionDetection<Dev, T> gdet;
  const std::size_t nc = gdet.detect(gb, gc, T(0), mu, stream);

  rbd::BodyManager<Host, T> cpu_manager(set);
  cpu_manager.syncDeviceFull();
  auto& hb = cpu_manager.device();
  rbd::Contacts<Host, T, Model> hc;
  rbd::CollisionDetection<Host, T> hdet;
  if (hdet.detect(hb, hc, T(0), mu) != nc) throw Error("accuracy: the backends found different contact counts");
  std::printf("%zu spheres, %zu contacts, model %s, dt %.4g\n\n", set.size() - 1, nc, opt.model.c_str(),
              double(rbd::SolverSettings<T>{}.dt));

  // Every solve starts from the velocities the pile was built with.
  const VectorD2<T, device_is<Dev>> gv0(gb.v), gw0(gb.w);
  const VectorD2<T, device_is<Host>> hv0(hb.v), hw0(hb.w);
  EventTimer timer(stream);
  rbd::JacobiSolver<Dev, T, Model, rbd::Gather> gpu_solver;
  for (double omega : opt.omegas) {
    gpu_solver.solve(gb, gc, rbd::SolverSettings<T>{}, stream);  // warm-up: scratch allocation, module load
    emit(csv, gpu, "jacobi", "gpu", omega, nc, curve(opt, omega, opt.repeats, [&](const auto& s, auto& st) {
           gb.v = gv0;
           gb.w = gw0;
           GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
           timer.start();
           st = gpu_solver.solve(gb, gc, s, stream);
           return timer.stop_ms() * 1e-3;
         }));
  }
  using Clock = std::chrono::steady_clock;
  const auto host_timed = [&](auto&& solve) {
    return [&, solve](const auto& s, auto& st) {
      hb.v = hv0;
      hb.w = hw0;
      const auto t0 = Clock::now();
      st = solve(s);
      return std::chrono::duration<double>(Clock::now() - t0).count();
    };
  };
  rbd::JacobiSolver<Host, T, Model, rbd::Gather> cpu_solver;
  cpu_solver.solve(hb, hc, rbd::SolverSettings<T>{});  // warm-up: scratch allocation, OpenMP threads
  emit(csv, gpu, "jacobi", "cpu", opt.cpu_omega, nc,
       curve(opt, opt.cpu_omega, opt.cpu_repeats,
             host_timed([&](const auto& s) { return cpu_solver.solve(hb, hc, s); })));
  emit(csv, gpu, "gauss_seidel", "cpu", opt.gs_omega, nc,
       curve(opt, opt.gs_omega, opt.cpu_repeats,
             host_timed([&](const auto& s) { return rbd::solve_gauss_seidel(hb, hc, s); })));
  GPUSOLVE_CUDA_CHECK(cudaStreamDestroy(stream));
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--contacts")
      o.contacts = parse_list<std::size_t>(option_value(argc, argv, i)).front();
    else if (a == "--omegas")
      o.omegas = parse_list<double>(option_value(argc, argv, i));
    else if (a == "--max-iters")
      o.max_iters = std::size_t(std::max(1, std::atoi(option_value(argc, argv, i).c_str())));
    else if (a == "--repeats")
      o.repeats = std::max(1, std::atoi(option_value(argc, argv, i).c_str()));
    else if (a == "--cpu-repeats")
      o.cpu_repeats = std::max(1, std::atoi(option_value(argc, argv, i).c_str()));
    else if (a == "--cpu-omega")
      o.cpu_omega = std::atof(option_value(argc, argv, i).c_str());
    else if (a == "--gs-omega")
      o.gs_omega = std::atof(option_value(argc, argv, i).c_str());
    else if (a == "--model" && i + 1 < argc && (std::string(argv[i + 1]) == "pyramid" ||
                                                std::string(argv[i + 1]) == "frictionless"))
      o.model = argv[++i];
    else if (a == "--csv")
      o.csv = option_value(argc, argv, i);
    else
      usage_exit(argv[0],
                 "[--contacts N] [--omegas W,W...] [--max-iters K] [--repeats R] [--cpu-repeats R]\n"
                 "          [--cpu-omega W] [--gs-omega W] [--model pyramid|frictionless] [--csv FILE]",
                 a);
  }
  return o;
}
}  // namespace

int main(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  try {
    const std::string gpu = print_banner("gpusolve bench: residual against iterations and time, one step (float)");
#if defined(_OPENMP)
    std::printf("CPU backend: OpenMP, %d threads\n", omp_get_max_threads());
#else
    std::printf("CPU backend: one thread (built without OpenMP)\n");
#endif
    std::printf("GPU Jacobi: Gather accumulation; times: median of %d (GPU) / %d (CPU) repeats; gauss_seidel is\n"
                "the sequential host reference (one thread)\n",
                opt.repeats, opt.cpu_repeats);
    std::FILE* csv = open_csv(opt.csv,
                              "gpu,solver,backend,omega,contacts,iterations,iterations_run,seconds_median,"
                              "seconds_min,seconds_max,residual");
    rbd::BodySet<T> set = pile_with_contacts<device::gpu, T>(opt.contacts);
    if (opt.model == "pyramid")
      run<rbd::PyramidFriction>(set, opt, csv, gpu);
    else
      run<rbd::Frictionless>(set, opt, csv, gpu);
    if (csv) std::fclose(csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "accuracy: %s\n", e.what());
    return 1;
  }
  return 0;
}
