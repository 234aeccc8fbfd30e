// The memory a World holds per body: the shared sphere pile (or the cube pile)
// of N bodies stepped S times at the library's defaults, then the bytes
// gpusolve's buffers hold (memory::memory_use) in the backend's memory, per
// body and per contact present, with the contacts' capacity beside their count.
//
// Run: gpusolve_bench_memory [--n 100000] [--scene pile|cubes] [--steps 300] [--backend cpu|gpu]
//
// GPU: the device memory the World holds (its bodies, contacts, warm start,
// grid, solver and scratch), not the CUDA context. CPU backend: the host
// memory, which also counts the BodyManager's staging store (up to sync_chunk
// bodies; on the GPU it is host memory and not counted).
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "gpusolve/memory/memory_use.hpp"
#include "gpusolve/rbd/world.hpp"
#include "shared_pile.hpp"
#include "timing.hpp"

namespace {
using namespace gpusolve;

template <class Device, class Kind>
void measure(const std::string& scene, std::size_t n, long steps) {
  auto set = scene == "cubes" ? bench::cube_pile<float>(n) : bench::shared_pile<float>(n);
  const std::size_t before = memory::memory_use<Kind>().now;
  rbd::World<Device, float> w(set, rbd::SolverSettings<float>{});
  const std::size_t built = memory::memory_use<Kind>().now - before;
  rbd::StepStats<float> st;
  for (long k = 0; k < steps; ++k) st = w.step();
  const auto use = memory::memory_use<Kind>();
  const double held = double(use.now - before), peak = double(use.peak - before);
  std::printf("%s n=%zu steps=%ld: %zu contacts (capacity %zu); bodies at construction %.1f B/body; "
              "after the steps %.1f B/body (peak %.1f), %.1f B per contact present\n",
              scene.c_str(), n, steps, st.solver.contacts, w.contacts().capacity(), double(built) / double(n),
              held / double(n), peak / double(n),
              st.solver.contacts ? (held - double(built)) / double(st.solver.contacts) : 0.0);
}
}  // namespace

int main(int argc, char** argv) {
  const char* usage = "[--n LIST] [--scene pile|cubes] [--steps S] [--backend cpu|gpu]";
  std::vector<std::size_t> sizes{100000};
  std::string scene = "pile", backend = "gpu";
  long steps = 300;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--n") sizes = bench::parse_list<std::size_t>(bench::option_value(argc, argv, i));
    else if (a == "--scene") scene = bench::option_value(argc, argv, i);
    else if (a == "--steps") steps = std::stol(bench::option_value(argc, argv, i));
    else if (a == "--backend") backend = bench::option_value(argc, argv, i);
    else bench::usage_exit(argv[0], usage, a);
  }
  if (scene != "pile" && scene != "cubes") bench::usage_exit(argv[0], usage, "--scene " + scene);
  if (backend != "gpu" && backend != "cpu") bench::usage_exit(argv[0], usage, "--backend " + backend);
  for (std::size_t n : sizes) {
    if (backend == "gpu")
      measure<device::gpu, memory::device>(scene, n, steps);
    else
      measure<device::cpu, memory::host>(scene, n, steps);
  }
}
