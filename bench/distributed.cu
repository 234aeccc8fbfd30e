// The shared sphere pile (docs/piles.md) as one DistributedWorld over however
// many ranks mpirun starts, on the CPU backend or with every rank's World on
// the one GPU (ranks sharing it):
//   mpirun -np R gpusolve_bench_distributed [--backend cpu|gpu] [--mode defaults|jacobi10|gauss-seidel]
//     [--transport mpi|nccl] [--n 100000 | --per-rank N] [--steps 300] [--skin D] [--spread] [--csv FILE]
// --mode: the library's defaults (APGD), projected Jacobi at exactly 10 iterations, or
// coloured Gauss-Seidel at the defaults. --per-rank N: weak scaling, a pile of N spheres per
// rank (N x R in all). On the GPU backend the ranks of a node take its GPUs in turn (use_rank_gpu).
// --transport: the solve's sums through host memory with MPI (the default), or from GPU to GPU
// with NCCL (a GPU per rank, a build that found NCCL); NCCL queues its exchanges on the solve's
// stream, so `exchange` is then the time to queue them and the solve's time holds the rest.
// --skin D: DistributedWorld::set_skin (m; the library's default where not given).
// --spread: each rank adds its share of the pile's lattice (shared_pile_part), not rank 0
// all of it: what a pile of hundreds of millions needs (rank 0 would hold it all at once).
// Measured over the last third of the steps, medians, each phase the slowest
// rank's: the whole step (host clock, every rank waits for the slowest at the
// step's end); `bodies`, bodies moved between ranks, the Worlds rebuilt (or
// their bodies checked) and read back; the World's detection, solve (without
// its exchanges) and integration (World::set_phase_timing); `exchange`, the
// solve's exchanges of sums and reductions, waits included. Over the last 200
// steps the largest penetration; at the end the contacts and shadows; the
// steps that rebuilt; the last step's contact imbalance (the most contacts a
// rank solved over the ranks' mean). Rank 0 prints a line and appends a CSV row.
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gpusolve/rbd/distributed/distributed_world.hpp"
#include "shared_pile.hpp"

using namespace gpusolve;
using T = float;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The phases of a step, in ms, each the slowest rank's.
constexpr int phases = 6;
constexpr const char* phase_names[phases] = {"step", "bodies", "detection", "solve", "exchange", "integration"};

struct Result {
  double ms[phases] = {}, penetration = 0;
  long rebuilds = 0;  // in the measured steps
  T skin = 0;         // the world's
  double imbalance = 0;  // the last step's: the most contacts a rank solved over the ranks' mean
  rbd::DistributedStats<T> last;
};

// The most contacts one rank solves over the ranks' mean (1: balanced), a collective.
double contact_imbalance(std::size_t mine) {
  double most = double(mine), all = double(mine);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return all > 0 ? most * ranks / all : 1.0;
}

template <class Device, class Method>
Result run(const rbd::BodySet<T>& scene, long steps, const rbd::SolverSettings<T>& s, rbd::RankTransport transport,
           T skin) {
  rbd::DistributedWorld<Device, T, rbd::ConeFriction, Method> world(MPI_COMM_WORLD, scene, s, std::nullopt, transport);
  world.set_phase_timing(true);
  if (skin >= 0) world.set_skin(skin);
  std::vector<double> measured[phases];
  Result r;
  r.skin = world.skin();
  for (long k = 0; k < steps; ++k) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    r.last = world.step();
    MPI_Barrier(MPI_COMM_WORLD);
    const auto& st = r.last;
    double ms[phases] = {std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
                         1e3 * st.seconds_bodies,
                         1e3 * st.local.time_detection,
                         1e3 * (st.local.time_solve - st.seconds_exchange),
                         1e3 * st.seconds_exchange,
                         1e3 * st.local.time_integration};
    MPI_Allreduce(MPI_IN_PLACE, ms, phases, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (k >= steps - steps / 3) {
      for (int p = 0; p < phases; ++p) measured[p].push_back(ms[p]);
      r.rebuilds += st.rebuilt;
    }
    if (k >= steps - 200) r.penetration = std::max(r.penetration, double(st.max_penetration));
  }
  for (int p = 0; p < phases; ++p) r.ms[p] = median(measured[p]);
  r.imbalance = contact_imbalance(r.last.local.solver.contacts);
  return r;
}

// The run at `mode`: APGD (the defaults), Jacobi (jacobi10) or coloured Gauss-Seidel.
template <class Device>
Result run_mode(const std::string& mode, const rbd::BodySet<T>& scene, long steps, const rbd::SolverSettings<T>& s,
                rbd::RankTransport transport, T skin) {
  if (mode == "jacobi10") return run<Device, rbd::Jacobi<rbd::Gather>>(scene, steps, s, transport, skin);
  if (mode == "gauss-seidel") return run<Device, rbd::ColouredGaussSeidel>(scene, steps, s, transport, skin);
  return run<Device, rbd::AcceleratedJacobi<rbd::Gather>>(scene, steps, s, transport, skin);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  std::size_t n = 100000;
  long steps = 300;
  std::size_t per_rank = 0;
  T skin = -1;  // the library's default
  bool spread = false;
  std::string csv, backend = "cpu", mode = "defaults", transport = "mpi";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--spread") {
      spread = true;
      continue;
    }
    if (i + 1 == argc) break;  // an option without its value
    const char* v = argv[++i];
    if (a == "--backend") backend = v;
    else if (a == "--mode") mode = v;
    else if (a == "--transport") transport = v;
    else if (a == "--per-rank") per_rank = std::stoul(v);
    else if (a == "--n") n = std::stoul(v);
    else if (a == "--steps") steps = std::stol(v);
    else if (a == "--skin") skin = std::stof(v);
    else if (a == "--csv") csv = v;
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (per_rank != 0) n = per_rank * std::size_t(ranks);
  rbd::BodySet<T> scene = spread ? bench::shared_pile_part<T>(n, std::size_t(rank), std::size_t(ranks))
                                 : bench::shared_pile<T>(n);
  if (!spread && rank != 0) scene.records().clear();  // rank 0 adds the scene; the world spreads it
  if ((mode != "defaults" && mode != "jacobi10" && mode != "gauss-seidel") || (transport != "mpi" && transport != "nccl")) {
    if (rank == 0)
      std::fprintf(stderr, "gpusolve_bench_distributed: --mode is defaults, jacobi10 or gauss-seidel, not '%s'; "
                   "--transport is mpi or nccl, not '%s'\n", mode.c_str(), transport.c_str());
    MPI_Finalize();
    return 2;
  }
  const rbd::RankTransport over = transport == "nccl" ? rbd::RankTransport::nccl : rbd::RankTransport::mpi_host;
  rbd::SolverSettings<T> s;
  if (mode == "jacobi10") s.max_iterations = 10, s.check_every = 10, s.tolerance = T(1e-30);  // runs all 10
  std::string gpu;
  if (backend == "gpu") {
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, rbd::use_rank_gpu(MPI_COMM_WORLD)) == cudaSuccess) gpu = prop.name;
  }
  Result r;
  try {
    r = backend == "gpu" ? run_mode<device::gpu>(mode, scene, steps, s, over, skin)
                         : run_mode<device::cpu>(mode, scene, steps, s, over, skin);
  } catch (const gpusolve::Error& e) {  // every rank throws alike
    if (rank == 0) std::fprintf(stderr, "gpusolve_bench_distributed: %s\n", e.what());
    MPI_Finalize();
    return 1;
  }
  if (rank == 0) {
    const int threads = std::getenv("OMP_NUM_THREADS") ? std::atoi(std::getenv("OMP_NUM_THREADS")) : 0;
    std::printf("%s%s%s, %s over %s, ranks %d (OMP_NUM_THREADS %d), %zu spheres, %ld steps: %.2f ms/step (bodies %.2f, detection "
                "%.2f, solve %.2f, exchange %.2f, integration %.2f), contacts %zu, shadows %zu, penetration %.4f%%, "
                "rebuilt before %ld of the %ld measured steps (skin %.3g%s), contact imbalance %.3f\n",
                backend.c_str(), gpu.empty() ? "" : " ", gpu.c_str(), mode.c_str(), transport.c_str(), ranks, threads, n, steps, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.ms[4], r.ms[5],
                r.last.contacts, r.last.shadows, 100 * r.penetration, r.rebuilds, steps / 3, double(r.skin),
                spread ? ", each rank adding its share" : "", r.imbalance);
    if (!csv.empty()) {
      FILE* f = std::fopen(csv.c_str(), "a");
      if (f) {
        std::fseek(f, 0, SEEK_END);
        if (std::ftell(f) == 0) {
          std::fprintf(f, "backend,ranks,threads_per_rank,n,steps");
          for (const char* p : phase_names) std::fprintf(f, ",ms_%s", p);
          std::fprintf(f, ",contacts,shadows,max_penetration,rebuilds,mode,gpu,per_rank,transport,skin,spread,imbalance\n");
        }
        std::fprintf(f, "%s,%d,%d,%zu,%ld", backend.c_str(), ranks, threads, n, steps);
        for (double x : r.ms) std::fprintf(f, ",%.4f", x);
        std::fprintf(f, ",%zu,%zu,%.6g,%ld,%s,%s,%zu,%s,%.6g,%d,%.4f\n", r.last.contacts, r.last.shadows,
                     r.penetration, r.rebuilds, mode.c_str(), gpu.c_str(), per_rank, transport.c_str(), double(r.skin),
                     int(spread), r.imbalance);
        std::fclose(f);
      }
    }
  }
  MPI_Finalize();
  return 0;
}
