// Time per projected-Jacobi iteration on the GPU, per accumulation strategy and contact model.
//
// Run: gpusolve_bench_jacobi [--contacts 26000,1000000] [--repeats 20] [--iters N] [--warmup 2] [--omega 0.3]
//                             [--persistent on|grid|off] [--csv FILE]
//
// For each target contact count a settled-looking pile (bench/pile.hpp) is built
// and collision detection runs once. Then, per model and strategy, each repeat
// times three solves with CUDA events, from the same velocities every time:
//   A: N1 = 10 iterations, residual checked once (at the end);
//   B: N1 + N iterations, residual checked once;
//   C: N1 + N iterations, residual checked after every iteration.
// per iteration = (B - A) / N: the setup (inverse blocks, contact grouping) and
//                 the final check cancel out;
// per check     = (C - B) / (N1 + N - 1): one residual max-reduction, read by
//                 the host, which waits for the GPU each time;
// graph         = the same iteration's two kernels (contacts, then bodies)
//                 captured N times into one CUDA graph once and replayed (SolverSettings::graphs makes solve()
//                 capture and update one per solve, which costs more than it saves).
// --persistent: on (the default) makes solve() run the iterations between
// checks as one persistent kernel at any size (one thread-block cluster where
// its grid fits in one: SolverSettings::persistent_clusters), grid the same
// launched cooperatively at every size, off launches them
// (SolverSettings::persistent_max_contacts at its largest or 0).
// The tolerance is the smallest positive float and divergence detection is
// off, so every solve runs its full count; the program checks that it did.
// barrier: the floor under the persistent kernel's iteration, an iteration
// program of nothing but one barrier (the cluster's or the grid's, as the
// solve's) on the grid the contacts get
// (per barrier = (time of 10 + N barriers - time of 10) / N, median of repeats).
// omega defaults to 0.3: on this close-packed pile (12 contacts per sphere) the
// pyramid model diverges from omega 0.5 up (bench/accuracy.cu shows it), and a
// timing should run on a converging solve.
// Bytes per iteration are modelled (CalcNextPhi and ResolveCollisions counted as
// two passes, as before JacobiContact fused them: an upper bound): every field a kernel touches is counted once
// per contact (or body) per kernel, body data gathered per contact side, no
// reuse between kernels or through caches (the 26k case fits in L2 entirely).
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "gpusolve/rbd/solvers/jacobi.hpp"
#include "pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;
using namespace gpusolve::bench;
using rbd::Atomic;
using rbd::Gather;
using rbd::UpdateCache;
using T = float;
using Dev = device::gpu;

struct Options {
  std::vector<std::size_t> contacts{26000, 1000000};
  int repeats = 20, warmup = 2;
  std::size_t iters = 0;  // 0: 100 up to 200k contacts, 40 beyond
  double omega = 0.3;
  bool persistent = true, clusters = true;
  std::string csv;
};

const char* name(UpdateCache) { return "update_cache"; }
const char* name(Atomic) { return "atomic"; }
const char* name(Gather) { return "gather"; }
const char* name(rbd::Frictionless) { return "frictionless"; }
const char* name(rbd::PyramidFriction) { return "pyramid"; }

// What is known of the contact set when counting bytes.
struct Census {
  std::size_t contacts, bodies, sides;  // sides: contact sides on a moving body
};

// Modelled device-memory bytes of one iteration (see the file comment).
template <class Model, class Strategy>
double bytes_per_iteration(const Census& c, std::size_t passes) {
  constexpr double R = Model::rows, f = 4;  // float
  const double nc = c.contacts, sides = c.sides, nb = c.bodies;
  const double frame = 3 * f * (Model::friction ? 3 : 1);
  const double geometry = 2 * f /*a, b*/ + frame + 6 * f /*ra, rb*/;
  const double next_phi = nc * (geometry + f /*phi0*/ + 12 * f /*v, w of a and b*/ + R * f /*rhs*/);
  const double resolve = nc * (geometry + R * f /*dinv*/ + R * f /*rhs*/ + 2 * R * f /*x read, write*/ +
                               (Model::friction ? f : 0) /*mu*/ + 2 * f /*inv_mass*/ + 18 * f /*inv_inertia*/ +
                               2 /*status*/);
  double acc = 0;
  if constexpr (std::is_same_v<Strategy, Atomic>)  // one phase: contacts read V + A, bodies write V' and zero an A
    acc = sides * 12 * f /*atomic read-modify-write of dv, dw*/ + nc * 12 * f /*dv, dw of a and b read with v, w*/ +
          nb * 24 * f /*v, w, dv, dw read; v, w written, dv, dw zeroed*/;
  else {
    acc = sides * (f /*slot*/ + 6 * f /*dv, dw*/) + nb * (2 * f /*start*/ + 12 * f /*v, w r/w*/);
    if constexpr (std::is_same_v<Strategy, UpdateCache>)  // each pass reads every rank; every non-head entry
      acc += passes * 2 * nc * f + (sides - nb) * 18 * f + nb * 6 * f;  // is added once (3 x 24 B)
    else
      acc += sides * 6 * f;  // the gather reads every entry
  }
  return next_phi + resolve + acc;
}

struct Row {
  std::string model, strategy;
  std::size_t launches;
  Spread iter_us, graph_us, check_us, setup_us;
  double bytes, residual, graph_diff;
};

template <class Model, class Strategy>
Row bench_strategy(rbd::Bodies<Dev, T>& bodies, rbd::Contacts<Dev, T, Model>& contacts, const Census& census,
                   const VectorD2<T, device_is<Dev>>& v0, const VectorD2<T, device_is<Dev>>& w0, std::size_t iters,
                   const Options& opt, cudaStream_t stream) {
  rbd::JacobiSolver<Dev, T, Model, Strategy> solver;
  const std::size_t n1 = 10, n2 = n1 + iters;
  EventTimer timer(stream);
  const auto restore = [&] {
    bodies.v = v0;
    bodies.w = w0;
    GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
  };
  rbd::SolverStats<T> last;
  const auto timed_solve = [&](std::size_t n, std::size_t check_every) {
    rbd::SolverSettings<T> s;
    s.tolerance = std::numeric_limits<T>::denorm_min();  // stops only on an exactly zero residual
    s.omega = T(opt.omega);
    s.divergence_checks = 0;
    s.max_retries = 0;  // time the iterations, not restarts at a lower omega
    s.persistent_max_contacts = opt.persistent ? ~std::size_t(0) : 0;
    s.persistent_clusters = opt.clusters;
    s.max_iterations = n;
    s.check_every = check_every;
    restore();
    timer.start();
    last = solver.solve(bodies, contacts, s, stream);
    const double ms = timer.stop_ms();
    if (last.iterations != n || last.status != rbd::SolverStatus::max_iterations) {
      std::fprintf(stderr, "jacobi: %s/%s stopped after %zu of %zu iterations (%s)\n", name(Model{}),
                   name(Strategy{}), last.iterations, n, rbd::to_string(last.status));
      std::exit(1);
    }
    return ms;
  };
  for (int w = 0; w < opt.warmup; ++w) timed_solve(n2, 1);
  std::vector<double> per_iter, per_check, setup;
  for (int r = 0; r < opt.repeats; ++r) {
    const double a = timed_solve(n1, n1), b = timed_solve(n2, n2), c = timed_solve(n2, 1);
    per_iter.push_back(1e3 * (b - a) / double(iters));
    per_check.push_back(1e3 * (c - b) / double(n2 - 1));
    setup.push_back(1e3 * a - n1 * per_iter.back());
  }
  timed_solve(n2, n2);
  const T residual = last.residual();
  VectorD2<T, device_is<Dev>> v_solve(bodies.v);

  // The same iteration as JacobiSolver::solve, captured n2 times into one graph,
  // as two kernels: the contacts, then the per-body sums (Atomic's solve() runs
  // the two in one phase, AtomicRotation; the velocities agree to rounding).
  using BV = typename rbd::Bodies<Dev, T>::View;
  using CV = typename rbd::Contacts<Dev, T, Model>::View;
  const std::size_t nc = contacts.size();
  rbd::Accumulator<Strategy, Dev, T> acc;
  VectorD2<T, device_is<Dev>> rhs(nc, Model::rows);
  VectorD1<T, device_is<Dev>> unused_residual(nc);
  const rbd::SolverSettings<T> defaults;
  const T omega = T(opt.omega), inv_dt = T(1) / defaults.dt;
  const auto fresh = [&] {
    restore();
    contacts.x.fill(T(0), stream);
    launch(Dev{}, nc, rbd::InverseBlocks<Model, BV, CV, T>{bodies.view(), contacts.view()}, stream);
    acc.prepare(bodies.view(), contacts.view(), stream);
    acc.passes();  // UpdateCache reads its pass count back once: not inside the capture
    GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(stream));
  };
  fresh();
  cudaGraph_t graph;
  cudaGraphExec_t exec;
  GPUSOLVE_CUDA_CHECK(cudaStreamBeginCapture(stream, cudaStreamCaptureModeThreadLocal));
  for (std::size_t it = 0; it < n2; ++it) {
    launch(Dev{}, nc,
           rbd::JacobiContact<Model, BV, CV, decltype(acc.sink()), T>{
               {bodies.view(), contacts.view(), rhs.view(), inv_dt, defaults.correction},
               {bodies.view(), contacts.view(), rhs.view(), acc.sink(), omega, false, unused_residual.view()}},
           stream);
    acc.apply(bodies.view(), stream);
  }
  GPUSOLVE_CUDA_CHECK(cudaStreamEndCapture(stream, &graph));
  std::size_t nodes = 0;
  GPUSOLVE_CUDA_CHECK(cudaGraphGetNodes(graph, nullptr, &nodes));
  GPUSOLVE_CUDA_CHECK(cudaGraphInstantiate(&exec, graph, 0));
  std::vector<double> graph_iter;
  double graph_diff = 0;
  for (int r = -1; r < opt.repeats; ++r) {  // r = -1: warm-up and the check against solve()
    fresh();
    timer.start();
    GPUSOLVE_CUDA_CHECK(cudaGraphLaunch(exec, stream));
    const double ms = timer.stop_ms();
    if (r >= 0) {
      graph_iter.push_back(1e3 * ms / double(n2));
      continue;
    }
    // Same work as solve(n2): the velocities must agree (to rounding for atomics).
    VectorD2<T> a(v_solve), b(bodies.v);
    for (std::size_t k = 0; k < bodies.size(); ++k)
      for (std::size_t c = 0; c < 3; ++c) graph_diff = std::fmax(graph_diff, std::fabs(double(a(k, c)) - b(k, c)));
  }
  GPUSOLVE_CUDA_CHECK(cudaGraphExecDestroy(exec));
  GPUSOLVE_CUDA_CHECK(cudaGraphDestroy(graph));

  Row row{name(Model{}), name(Strategy{}), nodes / n2, spread(per_iter), spread(graph_iter), spread(per_check),
          spread(setup), bytes_per_iteration<Model, Strategy>(census, acc.passes()), double(residual), graph_diff};
  return row;
}

// An iteration program of one grid barrier and nothing else.
struct BarrierOnly {
  template <class E>
  __device__ void operator()(const E& e, std::size_t, bool) const {
    e.sync();
  }
};

// us per barrier of the persistent kernel on the grid `width` indices get.
Spread barrier_us(std::size_t width, std::size_t iters, const Options& opt, cudaStream_t stream, std::size_t& blocks,
                  bool& clustered) {
  rbd::detail::PersistentLoop<Dev, T> loop;
  loop.set_clusters(opt.clusters);
  EventTimer timer(stream);
  const auto timed = [&](std::size_t n) {
    timer.start();
    loop.run(rbd::detail::NoStart{}, BarrierOnly{}, n, width, stream);
    return timer.stop_ms();
  };
  for (int w = 0; w < opt.warmup; ++w) timed(10 + iters);
  std::vector<double> us;
  for (int r = 0; r < opt.repeats; ++r) {
    const double a = timed(10), b = timed(10 + iters);
    us.push_back(1e3 * (b - a) / double(iters));
  }
  blocks = loop.blocks();
  clustered = loop.clustered();
  return spread(us);
}

void print_row(const Row& r, std::size_t nc) {
  const double s = r.iter_us.median * 1e-6;
  std::printf("%-12s %-12s %3zu %9.1f [%8.1f %8.1f] %9.1f [%8.1f %8.1f] %8.1f %9.1f %10.3g %8.1f %8.1f %9.2e %8.1e\n",
              r.model.c_str(), r.strategy.c_str(), r.launches, r.iter_us.median, r.iter_us.p10, r.iter_us.p90,
              r.graph_us.median, r.graph_us.p10, r.graph_us.p90, r.check_us.median, r.setup_us.median, nc / s,
              r.bytes / s / 1e9, r.bytes / (r.graph_us.median * 1e-6) / 1e9, r.residual, r.graph_diff);
}

template <class Model>
void bench_model(rbd::BodySet<T>& set, const Options& opt, std::size_t target, std::FILE* csv, const std::string& gpu,
                 cudaStream_t stream) {
  rbd::BodyManager<Dev, T> manager(set);
  manager.syncDeviceFull(stream);
  auto& bodies = manager.device();
  rbd::Contacts<Dev, T, Model> contacts;
  rbd::CollisionDetection<Dev, T> detection;
  const std::size_t nc = detection.detect(bodies, contacts, T(0), rbd::SolverSettings<T>{}.friction, stream);
  GPUSOLVE_CUDA_CHECK(cudaStreamSynchronize(stream));
  // Contact sides on moving bodies: every contact has a sphere as a; b is the floor or a sphere.
  VectorD1<std::uint32_t> b_host(contacts.b);
  const std::uint32_t floor = std::uint32_t(set.size() - 1);
  std::size_t on_floor = 0;
  for (std::size_t i = 0; i < nc; ++i) on_floor += b_host(i) == floor;
  const Census census{nc, bodies.size(), 2 * nc - on_floor};
  const std::size_t iters = opt.iters ? opt.iters : (nc <= 200000 ? 100 : 40);
  const VectorD2<T, device_is<Dev>> v0(bodies.v), w0(bodies.w);
  std::printf("\n%s: %zu contacts (target %zu; %zu on the floor), %zu spheres; N = %zu timed iterations, %d repeats,"
              " omega %.2f\n",
              name(Model{}), nc, target, on_floor, set.size() - 1, iters, opt.repeats, opt.omega);
  std::printf("%-12s %-12s %3s %9s %19s %9s %19s %8s %9s %10s %8s %8s %9s %8s\n", "model", "strategy", "L/i",
              "us/iter", "[p10 p90]", "graph", "[p10 p90]", "us/check", "setup us", "contacts/s", "GB/s", "graphGB/s",
              "residual", "|dv|");
  if (opt.persistent) {
    std::size_t blocks = 0;
    bool clustered = false;
    const Spread b = barrier_us(nc, iters, opt, stream, blocks, clustered);
    std::printf("%-12s %-12s %3s %9.1f [%8.1f %8.1f]  (one %s barrier of the persistent kernel, %zu blocks of %u)\n",
                name(Model{}), "barrier", "-", b.median, b.p10, b.p90, clustered ? "cluster" : "grid", blocks,
                rbd::detail::persistent_block_size);
  }
  std::vector<Row> rows;
  rows.push_back(bench_strategy<Model, UpdateCache>(bodies, contacts, census, v0, w0, iters, opt, stream));
  print_row(rows.back(), nc);
  rows.push_back(bench_strategy<Model, Atomic>(bodies, contacts, census, v0, w0, iters, opt, stream));
  print_row(rows.back(), nc);
  rows.push_back(bench_strategy<Model, Gather>(bodies, contacts, census, v0, w0, iters, opt, stream));
  print_row(rows.back(), nc);
  if (!csv) return;
  for (const Row& r : rows)
    std::fprintf(csv,
                 "\"%s\",%zu,%zu,%zu,%s,%s,%s,%zu,%zu,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.0f,%.6g,"
                 "%.3g\n",
                 gpu.c_str(), nc, target, set.size() - 1, r.model.c_str(), r.strategy.c_str(),
                 opt.persistent ? (opt.clusters ? "on" : "grid") : "off", r.launches, iters,
                 opt.repeats, r.iter_us.median, r.iter_us.p10, r.iter_us.p90, r.iter_us.min, r.iter_us.max,
                 r.graph_us.median, r.graph_us.p10, r.graph_us.p90, r.check_us.median, r.setup_us.median,
                 nc / (r.iter_us.median * 1e-6), r.bytes, r.residual, r.graph_diff);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--contacts")
      o.contacts = parse_list<std::size_t>(option_value(argc, argv, i));
    else if (a == "--repeats")
      o.repeats = std::max(1, std::atoi(option_value(argc, argv, i).c_str()));
    else if (a == "--warmup")
      o.warmup = std::max(0, std::atoi(option_value(argc, argv, i).c_str()));
    else if (a == "--iters")
      o.iters = std::size_t(std::max(1, std::atoi(option_value(argc, argv, i).c_str())));
    else if (a == "--omega")
      o.omega = std::atof(option_value(argc, argv, i).c_str());
    else if (a == "--persistent") {
      const std::string v = option_value(argc, argv, i);
      if (v != "on" && v != "grid" && v != "off") throw InvalidArgumentError("bench: --persistent takes on, grid or off");
      o.persistent = v != "off", o.clusters = v == "on";
    } else if (a == "--csv")
      o.csv = option_value(argc, argv, i);
    else
      usage_exit(argv[0],
                 "[--contacts N,N...] [--repeats R] [--warmup W] [--iters N] [--omega W] [--persistent on|grid|off] "
                 "[--csv FILE]",
                 a);
  }
  return o;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    const Options opt = parse(argc, argv);
    const std::string gpu = print_banner("gpusolve bench: projected Jacobi iteration (float)");
    std::printf(
        "JacobiSolver::solve runs the iterations between two checks as one persistent kernel (persistent on: one\n"
        "thread-block cluster up to 16 blocks, grid: cooperative at any size) or launches each iteration's kernels\n"
        "(off); the host waits for the GPU only at a check.\n"
        "us/iter: solve() with one check; graph: the launches' kernels from a graph captured once\n"
        "and replayed (no capture cost); us/check: one residual check with its host sync; L/i: launches/iteration;\n"
        "GB/s: modelled bytes (see source) / time; |dv|: max velocity difference graph vs solve() (0: same work).\n");
    std::FILE* csv = open_csv(
        opt.csv,
        "gpu,contacts,target,spheres,model,strategy,persistent,launches_per_iter,iters,repeats,us_per_iter_median,"
        "us_per_iter_p10,us_per_iter_p90,us_per_iter_min,us_per_iter_max,graph_us_per_iter_median,"
        "graph_us_per_iter_p10,graph_us_per_iter_p90,us_per_check_median,setup_us_median,contacts_per_s,"
        "modelled_bytes_per_iter,final_residual,graph_vs_solve_max_dv");
    std::printf("solve(): persistent %s\n", opt.persistent ? (opt.clusters ? "on" : "grid") : "off");
    cudaStream_t stream;
    GPUSOLVE_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
    for (std::size_t target : opt.contacts) {
      rbd::BodySet<T> set = pile_with_contacts<Dev, T>(target);
      bench_model<rbd::Frictionless>(set, opt, target, csv, gpu, stream);
      bench_model<rbd::PyramidFriction>(set, opt, target, csv, gpu, stream);
    }
    GPUSOLVE_CUDA_CHECK(cudaStreamDestroy(stream));
    if (csv) std::fclose(csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "jacobi: %s\n", e.what());
    return 1;
  }
  return 0;
}
