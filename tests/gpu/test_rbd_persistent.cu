// The persistent solver kernel (execution/persistent_loop.hpp) against the same
// iterations launched one kernel at a time: the same functors in the same
// order, so Jacobi's two deterministic strategies and coloured Gauss-Seidel
// agree bit for bit; APGD's momentum sums its restart test in another order,
// so it agrees to rounding.
// These scenes' kernels fit in one thread-block cluster; at the end, the
// cluster against the cooperative grid.
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// One solve by `Solver` on the GPU; runs to the cap unless `tune` lowers it
// or changes the tolerance or omega.
template <class Solver, class Tune = void (*)(SolverSettings<float>&)>
std::pair<std::vector<float>, SolverStats<float>> solve_with(bool persistent, std::size_t check_every,
                                                             Tune tune = [](SolverSettings<float>&) {}) {
  auto set = pile<float>(6, 5);
  BodyManager<device::gpu, float> m(set);
  m.syncDeviceFull();
  Contacts<device::gpu, float, ConeFriction> c;
  SolverSettings<float> s;
  s.dt = 0.01f, s.margin = 0.02f, s.friction = 0.4f;
  s.tolerance = 1e-6f, s.max_iterations = 120, s.check_every = check_every;
  tune(s);
  s.persistent_max_contacts = persistent ? ~std::size_t(0) : 0;
  prepare_solve(m.device(), c, s);
  const auto stats = Solver().solve(m.device(), c, s);
  Bodies<device::cpu, float> host;
  host = m.device();
  return {velocities(host), stats};
}

template <class Strategy, class MomentumTag, class Tune = void (*)(SolverSettings<float>&)>
std::pair<std::vector<float>, SolverStats<float>> solve_once(bool persistent, std::size_t check_every,
                                                             Tune tune = [](SolverSettings<float>&) {}) {
  return solve_with<JacobiSolver<device::gpu, float, ConeFriction, Strategy, MomentumTag>>(persistent, check_every,
                                                                                           tune);
}

// The checks' figures of two solves, and the velocities they leave, the same.
template <class Run>
void check_same_solve(const Run& a, const Run& b) {
  CHECK(a.first == b.first);
  CHECK(a.second.status == b.second.status);
  CHECK(a.second.iterations == b.second.iterations);
  CHECK(a.second.total_iterations == b.second.total_iterations);
  CHECK(a.second.retries == b.second.retries);
  CHECK(a.second.omega == b.second.omega);
  CHECK(a.second.residuals == b.second.residuals);
  CHECK(a.second.checked_at == b.second.checked_at);
}

std::vector<float> positions(const BodySet<float>& set) {
  std::vector<float> out;
  for (std::size_t i = 0; i < set.size(); ++i)
    for (int k = 0; k < 3; ++k) out.push_back(set[i].pos[k]);
  return out;
}

}  // namespace

TEST_CASE("GPU persistent Jacobi kernel equals the launches bit for bit", "[rbd_persistent][gpu]") {
  // check_every 120: one kernel per solve; 7: a kernel per run between checks, the last one short.
  for (std::size_t every : {std::size_t(120), std::size_t(7)}) {
    INFO("check_every " << every);
    const auto gather = solve_once<Gather, NoMomentum>(true, every);
    const auto gather_launched = solve_once<Gather, NoMomentum>(false, every);
    REQUIRE(gather.second.contacts > 300);
    CHECK(gather.second.iterations == 120);
    CHECK(gather.first == gather_launched.first);
    CHECK(gather.second.residuals == gather_launched.second.residuals);
    const auto cache = solve_once<UpdateCache, NoMomentum>(true, every);
    CHECK(cache.second.reduction_passes > 1);
    CHECK(cache.first == solve_once<UpdateCache, NoMomentum>(false, every).first);
    CHECK(max_abs_diff(cache.first, gather.first) < 1e-4f);  // same iteration, summed in another order
  }
}

// The persistent kernel applies the residual checks itself (ConvergenceRule on
// the device); the launches read each check back. Both must stop at the same
// check for the same reason and leave the same bits.
TEST_CASE("GPU persistent kernel stops at the same check as the launches: converged, diverged, retried",
          "[rbd_persistent][gpu]") {
  const auto same = [](const auto& a, const auto& b) { check_same_solve(a, b); };
  {
    INFO("converges at a check before the cap");
    const auto tune = [](SolverSettings<float>& s) { s.tolerance = 1e-3f, s.max_iterations = 2000; };
    const auto fused = solve_once<Gather, NoMomentum>(true, 5, tune);
    REQUIRE(fused.second.status == SolverStatus::converged);
    CHECK(fused.second.iterations > 100);  // on the CPU backend: 545, after 109 checks
    CHECK(fused.second.iterations < 2000);
    CHECK(fused.second.checked_at.size() == fused.second.iterations / 5);
    same(fused, solve_once<Gather, NoMomentum>(false, 5, tune));
  }
  {
    INFO("over-relaxed: diverges, then converges on a retry at a smaller omega");
    const auto tune = [](SolverSettings<float>& s) {
      s.omega = 1.9f, s.tolerance = 2e-2f, s.max_iterations = 2000, s.max_retries = 3;
    };
    const auto fused = solve_once<Gather, NoMomentum>(true, 10, tune);
    REQUIRE(fused.second.retries >= 1);
    CHECK(fused.second.total_iterations > fused.second.iterations);
    same(fused, solve_once<Gather, NoMomentum>(false, 10, tune));
  }
  {
    INFO("over-relaxed without retries: reported diverged");
    const auto tune = [](SolverSettings<float>& s) { s.omega = 1.9f, s.max_iterations = 2000, s.max_retries = 0; };
    const auto fused = solve_once<Gather, NoMomentum>(true, 10, tune);
    CHECK(fused.second.status == SolverStatus::diverged);
    same(fused, solve_once<Gather, NoMomentum>(false, 10, tune));
  }
}

// Coloured Gauss-Seidel's colours as phases of one kernel: each colour's
// contacts update the same bodies in the same order as a launch per colour.
TEST_CASE("GPU persistent coloured Gauss-Seidel equals a launch per colour bit for bit", "[rbd_persistent][gpu]") {
  using GaussSeidel = ColouredGaussSeidelSolver<device::gpu, float, ConeFriction>;
  for (std::size_t every : {std::size_t(120), std::size_t(7)}) {
    INFO("check_every " << every);
    const auto fused = solve_with<GaussSeidel>(true, every);
    REQUIRE(fused.second.contacts > 300);
    CHECK(fused.second.colours >= 6);
    CHECK(fused.second.iterations == 120);
    check_same_solve(fused, solve_with<GaussSeidel>(false, every));
  }
  {
    INFO("converges at a check before the cap");
    const auto tune = [](SolverSettings<float>& s) { s.tolerance = 1e-3f, s.max_iterations = 2000; };
    const auto fused = solve_with<GaussSeidel>(true, 5, tune);
    CHECK(fused.second.status == SolverStatus::converged);
    CHECK(fused.second.iterations < 2000);
    check_same_solve(fused, solve_with<GaussSeidel>(false, 5, tune));
  }
  {
    INFO("over-relaxed: its residual grows, a retry at a smaller omega converges, on the device as on the host");
    const auto tune = [](SolverSettings<float>& s) {
      s.omega = 1.8f, s.divergence_growth = 1.05f, s.tolerance = 2e-2f, s.max_iterations = 2000, s.max_retries = 3;
    };
    const auto fused = solve_with<GaussSeidel>(true, 10, tune);
    CHECK(fused.second.retries >= 1);
    check_same_solve(fused, solve_with<GaussSeidel>(false, 10, tune));
  }
}

TEST_CASE("GPU persistent APGD kernel agrees with the launches", "[rbd_persistent][gpu]") {
  for (std::size_t every : {std::size_t(120), std::size_t(7)}) {
    INFO("check_every " << every);
    const auto fused = solve_once<Gather, Nesterov>(true, every);
    const auto launched = solve_once<Gather, Nesterov>(false, every);
    CHECK(fused.second.iterations == launched.second.iterations);
    CHECK(max_abs_diff(fused.first, launched.first) < 1e-3f);
    CHECK(fused.second.residual() < 10 * launched.second.residual() + 1e-4f);
    CHECK(launched.second.residual() < 10 * fused.second.residual() + 1e-4f);
  }
}

TEST_CASE("GPU World steps with the persistent kernel as with launches", "[rbd_persistent][gpu]") {
  auto run = [](bool persistent) {
    auto set = pile<float>(5, 4);
    SolverSettings<float> s;
    s.persistent_max_contacts = persistent ? ~std::size_t(0) : 0;
    World<device::gpu, float, ConeFriction, Jacobi<Gather>> w(set, s);
    std::vector<std::size_t> iterations;
    for (int i = 0; i < 40; ++i) iterations.push_back(w.step().solver.iterations);
    w.syncHost();
    return std::make_pair(positions(set), iterations);
  };
  const auto fused = run(true);
  CHECK(fused == run(false));
  CHECK(fused.second.back() > 0);
}

// Under the persistent kernel the World reads the solver's verdict with the
// step's figures, not after the solve (JacobiSolver::solve_queued): the
// statistics must be those the launches give, read at once or a step late,
// retries on the device included (omega 1.9 diverges on this pile).
TEST_CASE("GPU World reads the persistent solver's verdict late, as the launches give it at once",
          "[rbd_persistent][gpu]") {
  for (const float omega : {0.f, 1.9f}) {
    INFO("omega " << omega);
    auto run = [omega](bool persistent) {
      auto set = pile<float>(5, 4);
      SolverSettings<float> s;
      s.omega = omega;
      s.tolerance = 1e-3f, s.max_iterations = 400, s.check_every = 10;
      s.persistent_max_contacts = persistent ? ~std::size_t(0) : 0;
      World<device::gpu, float, ConeFriction, Jacobi<Gather>> w(set, s);
      std::vector<SolverStats<float>> at_once, late;
      for (int i = 0; i < 30; ++i) {
        w.advance(1);
        if (i > 0) late.push_back(w.previous_stats().solver);
        at_once.push_back(w.latest_stats().solver);
      }
      at_once.pop_back();  // the last step has no later read
      w.syncHost();
      return std::make_tuple(positions(set), at_once, late);
    };
    const auto [x, at_once, late] = run(true);
    const auto [x_launched, at_once_launched, late_launched] = run(false);
    CHECK(x == x_launched);
    REQUIRE(at_once.size() == at_once_launched.size());
    std::size_t retried = 0;
    for (std::size_t i = 0; i < at_once.size(); ++i) {
      INFO("step " << i);
      for (const auto* other : {&at_once_launched[i], &late[i]}) {
        CHECK(at_once[i].status == other->status);
        CHECK(at_once[i].contacts == other->contacts);
        CHECK(at_once[i].iterations == other->iterations);
        CHECK(at_once[i].total_iterations == other->total_iterations);
        CHECK(at_once[i].retries == other->retries);
        CHECK(at_once[i].omega == other->omega);
        CHECK(at_once[i].residuals == other->residuals);
        CHECK(at_once[i].checked_at == other->checked_at);
      }
      retried += at_once[i].retries > 0;
    }
    if (omega > 1.f) CHECK(retried > 0);
    CHECK(at_once.back().contacts > 0);
  }
}

namespace {
// Iteration k of a program whose second phase reads what other blocks wrote
// in its first: a[i] = k n + i, then b[i] += a[n - 1 - i]. A barrier that
// did not order global memory between blocks would leave other sums.
struct Mirror {
  std::uint32_t *a, *b;
  std::size_t n;
  template <class E>
  __device__ void operator()(const E& e, std::size_t k, bool) const {
    e.each(n, [&](std::size_t i) { a[i] = std::uint32_t(k * n + i); });
    e.sync();
    e.each(n, [&](std::size_t i) { b[i] += a[n - 1 - i]; });
    e.sync();
  }
};
}  // namespace

// A persistent grid of at most 16 blocks runs as one thread-block cluster on
// sm_90 and later (SolverSettings::persistent_clusters): its phases are
// separated by the cluster's barrier, a larger grid's by the grid's, a grid of
// one block's by the block's.
TEST_CASE("GPU persistent kernel: one cluster or the cooperative grid, ordered by its barrier",
          "[rbd_persistent][gpu]") {
  int dev = 0, clusters = 0;
  GPUSOLVE_CUDA_CHECK(cudaGetDevice(&dev));
  GPUSOLVE_CUDA_CHECK(cudaDeviceGetAttribute(&clusters, cudaDevAttrClusterLaunch, dev));
  if (!clusters) WARN("this GPU has no thread-block clusters: every run below is a cooperative grid");
  const std::size_t count = 50, block = rbd::detail::persistent_block_size,
                    cluster = rbd::detail::persistent_max_cluster;
  for (const bool on : {true, false})
    for (const std::size_t n : {std::size_t(200), std::size_t(1000), cluster * block, std::size_t(50000)}) {
      INFO("clusters " << on << ", " << n << " indices");
      VectorD1<std::uint32_t, device_is<device::gpu>> a(n), b(n);
      b.fill(0u);
      rbd::detail::PersistentLoop<device::gpu, float> loop;
      loop.set_clusters(on);
      loop.run(rbd::detail::NoStart{}, Mirror{a.data(), b.data(), n}, count, n, stream_t{});
      GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
      CHECK(loop.blocks() <= (n + block - 1) / block);
      CHECK((!loop.clustered() || loop.blocks() <= cluster));
      if (clusters && n == 1000) CHECK(loop.clustered() == on);
      if (n == 50000) CHECK_FALSE(loop.clustered());
      if (n == 200) CHECK(loop.blocks() == 1);  // the block's own barrier (one_block_grid)
      const VectorD1<std::uint32_t> host(b);
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < n; ++i)
        wrong += host(i) != std::uint32_t(n * count * (count + 1) / 2 + count * (n - 1 - i));
      CHECK(wrong == 0);
    }
}

// The cluster runs the cooperative grid's blocks and splits every sum the
// same way, so both give the same bits, with APGD's momentum too.
TEST_CASE("GPU persistent kernel as one cluster equals the cooperative grid bit for bit", "[rbd_persistent][gpu]") {
  const auto grid = [](SolverSettings<float>& s) { s.persistent_clusters = false; };
  for (std::size_t every : {std::size_t(120), std::size_t(7)}) {
    INFO("check_every " << every);
    CHECK(solve_once<Gather, NoMomentum>(true, every).first == solve_once<Gather, NoMomentum>(true, every, grid).first);
    const auto apgd = solve_once<Gather, Nesterov>(true, every);
    const auto apgd_grid = solve_once<Gather, Nesterov>(true, every, grid);
    CHECK(apgd.first == apgd_grid.first);
    CHECK(apgd.second.residuals == apgd_grid.second.residuals);
    CHECK(apgd.second.iterations == apgd_grid.second.iterations);
  }
}
