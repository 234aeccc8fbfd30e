// The shared sphere pile (docs/piles.md) as one DistributedWorld over however
// many ranks mpirun starts, on the CPU backend or with every rank's World on
// the one GPU (ranks sharing it):
//   mpirun -np R gpusolve_bench_distributed [--backend cpu|gpu] [--n 100000] [--steps 300] [--csv FILE]
// Measured over the last third of the steps, medians: the whole step (host
// clock, every rank waits for the slowest at the step's end), the exchange
// (bodies before the step plus the solve's exchanges; the slowest rank's),
// and the World's step; over the last 200 steps the largest penetration; at
// the end the contacts and shadows. Rank 0 prints a line and appends a CSV row.
// Host clock: a step ends with the host reading its figures, on either backend.
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

struct Result {
  double ms = 0, exchange = 0, world = 0, penetration = 0;
  long rebuilds = 0;  // in the measured steps
  rbd::DistributedStats<T> last;
};

template <class Device>
Result run(const rbd::BodySet<T>& scene, long steps) {
  rbd::DistributedWorld<Device, T> world(MPI_COMM_WORLD, scene, rbd::SolverSettings<T>{});
  std::vector<double> total, exchange, stepping;
  Result r;
  for (long k = 0; k < steps; ++k) {
    MPI_Barrier(MPI_COMM_WORLD);
    const auto start = std::chrono::steady_clock::now();
    r.last = world.step();
    MPI_Barrier(MPI_COMM_WORLD);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    double ex = 1e3 * r.last.seconds_exchange;
    MPI_Allreduce(MPI_IN_PLACE, &ex, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (k >= steps - steps / 3) {
      total.push_back(ms), exchange.push_back(ex), stepping.push_back(1e3 * r.last.seconds_step);
      r.rebuilds += r.last.rebuilt;
    }
    if (k >= steps - 200) r.penetration = std::max(r.penetration, double(r.last.max_penetration));
  }
  r.ms = median(total), r.exchange = median(exchange), r.world = median(stepping);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  std::size_t n = 100000;
  long steps = 300;
  std::string csv, backend = "cpu";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--backend") backend = argv[i + 1];
    else if (a == "--n") n = std::stoul(argv[i + 1]);
    else if (a == "--steps") steps = std::stol(argv[i + 1]);
    else if (a == "--csv") csv = argv[i + 1];
  }
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  rbd::BodySet<T> scene = bench::shared_pile<T>(n);
  if (rank != 0) scene.records().clear();  // rank 0 adds the scene; the world spreads it
  const Result r = backend == "gpu" ? run<device::gpu>(scene, steps) : run<device::cpu>(scene, steps);
  if (rank == 0) {
    const int threads = std::getenv("OMP_NUM_THREADS") ? std::atoi(std::getenv("OMP_NUM_THREADS")) : 0;
    std::printf("%s, ranks %d (OMP_NUM_THREADS %d), %zu spheres, %ld steps: %.2f ms/step, exchange %.2f ms (%.0f%%), "
                "contacts %zu, shadows %zu, penetration %.4f%%, rebuilt before %ld of the %ld measured steps\n",
                backend.c_str(), ranks, threads, n, steps, r.ms, r.exchange, 100 * r.exchange / r.ms, r.last.contacts,
                r.last.shadows, 100 * r.penetration, r.rebuilds, steps / 3);
    if (!csv.empty()) {
      FILE* f = std::fopen(csv.c_str(), "a");
      if (f) {
        std::fseek(f, 0, SEEK_END);
        if (std::ftell(f) == 0)
          std::fprintf(f, "backend,ranks,threads_per_rank,n,steps,ms_per_step,ms_exchange,ms_world_step,contacts,shadows,"
                          "max_penetration,rebuilds\n");
        std::fprintf(f, "%s,%d,%d,%zu,%ld,%.4f,%.4f,%.4f,%zu,%zu,%.6g,%ld\n", backend.c_str(), ranks, threads, n, steps,
                     r.ms, r.exchange, r.world, r.last.contacts, r.last.shadows, r.penetration, r.rebuilds);
        std::fclose(f);
      }
    }
  }
  MPI_Finalize();
  return 0;
}
