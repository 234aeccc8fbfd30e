// gpusolve_scenes: the thesis's scenes (ballpark, well, hopper) and blocks (every shape) on either backend, with
// per-step statistics, a JSON summary and frames for ParaView and POV-Ray.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "gpusolve/rbd/io/povray_writer.hpp"
#include "gpusolve/rbd/io/snapshot.hpp"
#include "gpusolve/rbd/io/vtk_writer.hpp"
#include "gpusolve/rbd/world.hpp"
#include "scene_ballpark.hpp"
#include "scene_blocks.hpp"
#include "scene_hopper.hpp"
#include "scene_options.hpp"
#include "scene_progress.hpp"
#include "scene_record.hpp"
#include "scene_well.hpp"

namespace scenes {
namespace {

using real = float;  // single precision, as the thesis
namespace rbd = gpusolve::rbd;

// The accumulation strategies by their command-line names; the first is the default.
const std::vector<std::string> accumulation_names{"gather", "cache", "atomic"};

// A scene behind one type, so that the run loop is compiled once per backend,
// model and strategy rather than once more per scene.
struct AnyScene {
  std::function<void(rbd::BodySet<real>&)> build;
  std::function<bool(long)> wants_edit;
  std::function<Changes(long, rbd::BodySet<real>&)> edit;
  rbd::io::PovOptions camera;
};

template <class S>
AnyScene erase(S& s) {
  return {[&s](rbd::BodySet<real>& b) { s.build(b); }, [&s](long step) { return s.wants_edit(step); },
          [&s](long step, rbd::BodySet<real>& b) { return s.edit(step, b); }, s.camera()};
}

std::string cpu_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string name = "CPU";
  for (std::string l; std::getline(in, l);)
    if (l.rfind("model name", 0) == 0) {
      name = l.substr(l.find(':') + 2);
      break;
    }
#if defined(_OPENMP)
  name += ", " + std::to_string(omp_get_max_threads()) + " OpenMP threads";
#else
  name += ", 1 thread";
#endif
  return name;
}

#if GPUSOLVE_HAS_NVCC
bool gpu_available() {
  int n = 0;
  return cudaGetDeviceCount(&n) == cudaSuccess && n > 0;
}
std::string gpu_name() {
  cudaDeviceProp p{};
  GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&p, 0));
  return p.name;
}
#endif

// Writes the frames the options ask for: spheres, moving shapes and fixed geometry as VTK, the whole scene as POV-Ray.
void write_frame(const Options& o, const rbd::io::Frame& f, const rbd::io::PovOptions& camera) {
  char name[32];
  std::snprintf(name, sizeof name, "%05zu", f.step);
  if (o.wants("vtk")) {
    rbd::io::write_vtk_spheres(o.out + "/frame_" + name + ".vtk", f);
    if (!f.capsules.empty() || std::any_of(f.boxes.begin(), f.boxes.end(), [](const auto& b) { return b.moving; }))
      rbd::io::write_vtk_shapes(o.out + "/shapes_" + name + ".vtk", f);
    rbd::io::write_vtk_fixed(o.out + "/fixed_" + name + ".vtk", f, 60.0);
  }
  if (o.wants("pov")) rbd::io::write_povray(o.out + "/frame_" + name + ".pov", f, camera);
}

// The run loop: build, step, edit, record, draw. Returns the process exit status.
template <class Device, class Model, class Method>
int run(const Options& o, AnyScene& scene, const std::string& device_name) {
  rbd::BodySet<real> set;
  scene.build(set);
  rbd::SolverSettings<real> s;
  s.dt = real(*o.dt);
  s.omega = real(o.omega);
  s.tolerance = real(*o.tolerance);
  s.max_iterations = static_cast<std::size_t>(*o.max_iterations);
  s.check_every = static_cast<std::size_t>(*o.check_every);
  s.friction = real(*o.friction);
  s.margin = real(o.margin);
  s.max_retries = static_cast<std::size_t>(o.max_retries);
  s.warm_start = real(o.warm_start);
  rbd::World<Device, real, Model, Method> world(set, s);
  world.set_phase_timing(true);  // the run record keeps each phase's time

  const bool gpu = std::is_same_v<Device, gpusolve::device::gpu>;
  const std::string accumulation =
      o.solver == "gauss-seidel" ? "none" : o.accumulation.empty() ? accumulation_names[0] : o.accumulation;
  RunRecord record(o.out, o.csv_every);
  Progress progress(o.scene, *o.steps, o.status_every, o.quiet);
  if (!o.quiet)
    std::fprintf(stderr, "%s on %s (%s): %zu bodies to start, %ld steps, writing to %s\n", o.scene.c_str(),
                 gpu ? "gpu" : "cpu", device_name.c_str(), set.size(), *o.steps, o.out.c_str());

  using Clock = std::chrono::steady_clock;
  for (long step = 0; step < *o.steps; ++step) {
    const auto t0 = Clock::now();
    if (scene.wants_edit(step)) {
      world.syncHost();  // the edit reads positions, and syncDevice writes all of them back
      const Changes c = scene.edit(step, set);
      for (std::size_t i : c.added) world.manager().bodyAdded(i);
      for (std::size_t i : c.removed) world.manager().bodyRemoved(i);
      world.manager().syncDevice();
    }
    const rbd::StepStats<real> st = world.step();
    const double t_step = std::chrono::duration<double>(Clock::now() - t0).count();
    const double time = (step + 1) * *o.dt;
    const std::size_t bodies = world.bodies().size();
    record.add(step, time, bodies, st, t_step);
    progress.update({step, time, bodies, st.solver.contacts, st.solver.iterations, double(st.solver.residual()),
                     double(st.max_penetration)});
    const bool last = step + 1 == *o.steps;
    if (!o.wants("none") && (last || (o.frame_every > 0 && (step + 1) % o.frame_every == 0))) {
      world.syncHost();
      write_frame(o, rbd::io::snapshot(set, static_cast<std::size_t>(step + 1), time), scene.camera);
    }
  }
  const std::string model = std::is_same_v<Model, rbd::Frictionless> ? "frictionless"
                            : std::is_same_v<Model, rbd::ConeFriction> ? "cone_friction"
                                                                         : "pyramid_friction";
  record.write_summary(o.out + "/summary.json", o, gpu ? "gpu" : "cpu", device_name, model, Method::name, accumulation,
                       progress.elapsed());
  if (!o.quiet)
    std::fprintf(stderr, "done in %s: max penetration %.4f, %ld divergence event(s); see %s/summary.json\n",
                 Progress::duration(progress.elapsed()).c_str(), record.max_penetration(),
                 record.divergence_events(), o.out.c_str());
  return record.divergence_events() == 0 ? 0 : 1;
}

template <class Device, class Model>
int with_method(const Options& o, AnyScene& scene, const std::string& dev) {
  if (o.solver == "gauss-seidel") return run<Device, Model, rbd::ColouredGaussSeidel>(o, scene, dev);
  if (o.solver == "apgd") return run<Device, Model, rbd::AcceleratedJacobi<rbd::Gather>>(o, scene, dev);
  if (o.solver == "substepping") return run<Device, Model, rbd::Substepping<>>(o, scene, dev);
  const std::string& a = o.accumulation.empty() ? accumulation_names[0] : o.accumulation;
  if (a == "cache") return run<Device, Model, rbd::Jacobi<rbd::UpdateCache>>(o, scene, dev);
  if (a == "atomic") return run<Device, Model, rbd::Jacobi<rbd::Atomic>>(o, scene, dev);
  return run<Device, Model, rbd::Jacobi<rbd::Gather>>(o, scene, dev);
}

template <class Device>
int with_model(const Options& o, AnyScene& scene, const std::string& dev) {
  if (*o.friction == 0.0) return with_method<Device, rbd::Frictionless>(o, scene, dev);
  if (o.friction_model == "pyramid") return with_method<Device, rbd::PyramidFriction>(o, scene, dev);
  return with_method<Device, rbd::ConeFriction>(o, scene, dev);
}

std::string defaults_text() {
  std::ostringstream os;
  auto line = [&os](const char* name, const SceneDefaults& d) {
    os << "  " << name << ": steps " << d.steps << ", scale " << d.scale << ", dt " << d.dt << ", tolerance "
       << d.tolerance << ", max-iterations " << d.max_iterations << ", check-every " << d.check_every
       << ", friction " << d.friction << '\n';
  };
  line("ballpark", Ballpark<real>::defaults());
  line("well    ", Well<real>::defaults());
  line("hopper  ", Hopper<real>::defaults());
  line("blocks  ", Blocks<real>::defaults());
  return os.str();
}

int main_(int argc, char** argv) {
  std::string names;
  for (const auto& n : accumulation_names) names += (names.empty() ? "" : ", ") + n;
  names += " [" + accumulation_names[0] + "]";
  Options o;
  try {
    o = parse_options(argc, argv, accumulation_names);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "gpusolve_scenes: %s\nTry 'gpusolve_scenes --help'.\n", e.what());
    return 2;
  }
  if (o.help) {
    std::fputs(usage(names, defaults_text()).c_str(), stdout);
    return 0;
  }

  std::string backend = o.backend;
#if GPUSOLVE_HAS_NVCC
  if (backend == "auto") backend = gpu_available() ? "gpu" : "cpu";
#else
  if (backend == "gpu") {
    std::fprintf(stderr,
                 "gpusolve_scenes: --backend gpu: this build has no CUDA backend (it was compiled without nvcc);"
                 " build gpusolve_scenes with CUDA or use --backend cpu\n");
    return 2;
  }
  backend = "cpu";
#endif

  // The scene objects outlive the run; only the chosen one is used.
  Ballpark<real> ballpark(o);
  Blocks<real> blocks(o);
  std::optional<Well<real>> well;
  std::optional<Hopper<real>> hopper;
  AnyScene scene;
  if (o.scene == "ballpark") {
    o.resolve(Ballpark<real>::defaults());
    scene = erase(ballpark);
  } else if (o.scene == "blocks") {
    o.resolve(Blocks<real>::defaults());
    scene = erase(blocks);
  } else if (o.scene == "well") {
    o.resolve(Well<real>::defaults());
    scene = erase(well.emplace(o));
  } else {
    o.resolve(Hopper<real>::defaults());
    scene = erase(hopper.emplace(o));
  }
  std::filesystem::create_directories(o.out);

#if GPUSOLVE_HAS_NVCC
  if (backend == "gpu") return with_model<gpusolve::device::gpu>(o, scene, gpu_name());
#endif
  return with_model<gpusolve::device::cpu>(o, scene, cpu_name());
}

}  // namespace
}  // namespace scenes

int main(int argc, char** argv) {
  try {
    return scenes::main_(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpusolve_scenes: %s\n", e.what());
    return 1;
  }
}
