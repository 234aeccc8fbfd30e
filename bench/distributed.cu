// The shared sphere pile (docs/piles.md) as one DistributedWorld over however
// many ranks mpirun starts, on the CPU backend or with every rank's World on
// the one GPU (ranks sharing it):
//   mpirun -np R gpusolve_bench_distributed [--backend cpu|gpu] [--method apgd|gauss-seidel] [--n 100000]
//     [--steps 300] [--csv FILE]
// Measured over the last third of the steps, medians, each phase the slowest
// rank's: the whole step (host clock, every rank waits for the slowest at the
// step's end); `bodies`, bodies moved between ranks, the Worlds rebuilt (or
// their bodies checked) and read back; the World's detection, solve (without
// its exchanges) and integration (World::set_phase_timing); `exchange`, the
// solve's exchanges of sums and reductions, waits included. Over the last 200
// steps the largest penetration; at the end the contacts and shadows; the
// steps that rebuilt. Rank 0 prints a line and appends a CSV row.
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
  rbd::DistributedStats<T> last;
};

template <class Device, class Method>
Result run(const rbd::BodySet<T>& scene, long steps) {
  rbd::DistributedWorld<Device, T, rbd::ConeFriction, Method> world(MPI_COMM_WORLD, scene, rbd::SolverSettings<T>{});
  world.set_phase_timing(true);
  std::vector<double> measured[phases];
  Result r;
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
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  std::size_t n = 100000;
  long steps = 300;
  std::string csv, backend = "cpu", method = "apgd";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--backend") backend = argv[i + 1];
    else if (a == "--method") method = argv[i + 1];
    else if (a == "--n") n = std::stoul(argv[i + 1]);
    else if (a == "--steps") steps = std::stol(argv[i + 1]);
    else if (a == "--csv") csv = argv[i + 1];
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  rbd::BodySet<T> scene = bench::shared_pile<T>(n);
  if (rank != 0) scene.records().clear();  // rank 0 adds the scene; the world spreads it
  if (method != "apgd" && method != "gauss-seidel") {
    if (rank == 0) std::fprintf(stderr, "gpusolve_bench_distributed: --method is apgd or gauss-seidel, not '%s'\n", method.c_str());
    MPI_Finalize();
    return 2;
  }
  using APGD = rbd::AcceleratedJacobi<rbd::Gather>;
  using GS = rbd::ColouredGaussSeidel;
  const bool gs = method == "gauss-seidel";
  const Result r = backend == "gpu" ? (gs ? run<device::gpu, GS>(scene, steps) : run<device::gpu, APGD>(scene, steps))
                                    : (gs ? run<device::cpu, GS>(scene, steps) : run<device::cpu, APGD>(scene, steps));
  if (rank == 0) {
    const int threads = std::getenv("OMP_NUM_THREADS") ? std::atoi(std::getenv("OMP_NUM_THREADS")) : 0;
    std::printf("%s, %s, ranks %d (OMP_NUM_THREADS %d), %zu spheres, %ld steps: %.2f ms/step (bodies %.2f, detection "
                "%.2f, solve %.2f, exchange %.2f, integration %.2f), contacts %zu, shadows %zu, penetration %.4f%%, "
                "rebuilt before %ld of the %ld measured steps\n",
                backend.c_str(), method.c_str(), ranks, threads, n, steps, r.ms[0], r.ms[1], r.ms[2], r.ms[3], r.ms[4], r.ms[5],
                r.last.contacts, r.last.shadows, 100 * r.penetration, r.rebuilds, steps / 3);
    if (!csv.empty()) {
      FILE* f = std::fopen(csv.c_str(), "a");
      if (f) {
        std::fseek(f, 0, SEEK_END);
        if (std::ftell(f) == 0) {
          std::fprintf(f, "backend,ranks,threads_per_rank,n,steps");
          for (const char* p : phase_names) std::fprintf(f, ",ms_%s", p);
          std::fprintf(f, ",contacts,shadows,max_penetration,rebuilds,method\n");
        }
        std::fprintf(f, "%s,%d,%d,%zu,%ld", backend.c_str(), ranks, threads, n, steps);
        for (double x : r.ms) std::fprintf(f, ",%.4f", x);
        std::fprintf(f, ",%zu,%zu,%.6g,%ld,%s\n", r.last.contacts, r.last.shadows, r.penetration, r.rebuilds,
                     method.c_str());
        std::fclose(f);
      }
    }
  }
  MPI_Finalize();
  return 0;
}
