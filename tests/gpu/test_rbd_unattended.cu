// Steps queued with no host wait (World::advance_unattended) on the GPU: the
// contact count stays on the device, the persistent kernel (a cluster or the
// cooperative grid), the launched solve and the warm start read it there; a
// step whose contacts outgrow the list is held and taken again; a NaN is
// reported with the body and the step, and nothing moves from there.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "catch_compat.hpp"
#include "../host/test_rbd_scenes.hpp"
#include "gpu_step_checks.hpp"

using namespace rbd_test;

namespace {

// What a run leaves: the bodies, the contacts of its last step, the figures of its last two steps.
struct Run {
  std::vector<float> state;
  std::size_t contacts = 0, requeued = 0;
  StepStats<float> last, previous;
};

template <class Method>
Run run(BodySet<float> set, const SolverSettings<float>& s, std::size_t steps, bool unattended) {
  World<device::gpu, float, ConeFriction, Method> w(set, s);
  if (unattended)
    w.advance_unattended(steps);
  else
    w.advance(steps);
  Run r;
  r.last = w.latest_stats(), r.previous = w.previous_stats();
  r.contacts = w.contacts().size();
  r.requeued = w.steps_requeued();
  w.syncHost();
  r.state = host_state(set);
  return r;
}

// Gather's sums have a fixed order whatever the grid: the bodies agree to the
// bit. The kinetic energy's sum runs over max(contacts, bodies) indices, the
// contacts' bound where the count is on the device: it agrees to rounding.
void same_run(const Run& a, const Run& b) {
  CHECK(a.state == b.state);
  CHECK(a.contacts == b.contacts);
  for (const auto& [x, y] : {std::make_pair(a.last, b.last), std::make_pair(a.previous, b.previous)}) {
    CHECK(x.solver.contacts == y.solver.contacts);
    CHECK(x.solver.iterations == y.solver.iterations);
    CHECK(x.solver.residual() == y.solver.residual());
    CHECK(x.max_penetration == y.max_penetration);
    CHECK(x.kinetic_energy == Approx(y.kinetic_energy).epsilon(1e-5));
  }
}

}  // namespace

TEST_CASE("GPU World: unattended steps equal advance() under the cluster, the grid and launches",
          "[rbd_step][gpu][unattended]") {
  struct Case {
    const char* name;
    std::size_t n, layers;
    bool clusters;
    std::size_t persistent_max;
  };
  for (const Case c : {Case{"cluster", 5, 4, true, 1000000}, Case{"grid", 5, 4, false, 1000000},
                       Case{"larger grid", 16, 5, true, 1000000}, Case{"launches", 5, 4, true, 0}}) {
    INFO(c.name);
    SolverSettings<float> s = settings();
    s.persistent_clusters = c.clusters;
    s.persistent_max_contacts = c.persistent_max;
    s.max_iterations = 60, s.check_every = 20;
    s.contacts_per_body = 4;  // room for every step's contacts: the path where no step is held
    const auto set = pile<float>(c.n, c.layers);
    const Run a = run<Jacobi<Gather>>(set, s, 30, false), b = run<Jacobi<Gather>>(set, s, 30, true);
    same_run(a, b);
    CHECK(a.last.solver.contacts > 4 * c.n * c.n);
    CHECK(b.requeued == 0);
  }
}

TEST_CASE("GPU World: unattended APGD and atomic Jacobi move the bodies as advance() does",
          "[rbd_step][gpu][unattended]") {
  // Their sums over the grid (APGD's restart test, the atomics) depend on the
  // grid's size and on the order of arrival, and a pile's motion amplifies
  // rounding: a few steps, agreement to well below what a wrong contact
  // would change (the margin keeps touching pairs away from its edge). The
  // atomics' order alone moved a body by 1.1e-3 within five steps here: two
  // steps for them (the first is taken attended).
  const auto set = pile<float>(8, 4);
  SolverSettings<float> s = settings();
  s.margin = 0.1f;
  auto close = [](const Run& a, const Run& b) {
    REQUIRE(a.state.size() == b.state.size());
    float worst = 0;
    for (std::size_t k = 0; k < a.state.size(); ++k) worst = std::fmax(worst, std::fabs(a.state[k] - b.state[k]));
    INFO("largest difference " << worst);
    CHECK(worst < 1e-4f);  // a contact applied twice or to the wrong body changes a velocity by about 1e-2
    CHECK(a.contacts == b.contacts);
    CHECK(a.last.solver.contacts == b.last.solver.contacts);
    CHECK(a.last.max_penetration == Approx(b.last.max_penetration).epsilon(1e-3));
  };
  close(run<AcceleratedJacobi<Gather>>(set, s, 5, false), run<AcceleratedJacobi<Gather>>(set, s, 5, true));
  close(run<Jacobi<Atomic>>(set, s, 2, false), run<Jacobi<Atomic>>(set, s, 2, true));
}

TEST_CASE("GPU World: an unattended step whose contacts outgrow the list is held and taken again",
          "[rbd_step][gpu][unattended]") {
  SolverSettings<float> s;
  s.gravity[2] = 0;
  s.margin = 0.5f;
  s.dt = 0.01f;
  const auto set = implosion<float>(6, 4.0f);
  const std::size_t capacity = 4 * set.size();
  std::vector<std::size_t> counts;
  {
    auto copy = set;
    World<device::gpu, float, ConeFriction, Jacobi<Gather>> w(copy, s);
    for (int i = 0; i < 12; ++i) counts.push_back(w.step().solver.contacts);
  }
  INFO("contacts per step: first " << counts.front() << ", last " << counts.back());
  REQUIRE(counts[3] <= capacity);
  REQUIRE(counts.back() > capacity);
  const Run a = run<Jacobi<Gather>>(set, s, 12, false), b = run<Jacobi<Gather>>(set, s, 12, true);
  same_run(a, b);
  CHECK(b.requeued > 0);
}

TEST_CASE("GPU World: a NaN met by unattended steps names the body and the step, and nothing moves",
          "[rbd_step][gpu][unattended]") {
  auto set = pile<float>(4, 3);
  World<device::gpu, float> w(set, settings());
  w.advance_unattended(5);
  w.syncHost();
  const std::vector<float> before = host_state(set);
  const std::size_t victim = 9;
  using BV = typename Bodies<device::gpu, float>::View;
  launch(device::gpu{}, 1, PoisonVelocity<BV>{w.bodies().view(), victim});
  w.advance_unattended(4);
  try {
    w.finish();
    FAIL("the steps ran with a NaN velocity");
  } catch (const NonFiniteStateError& e) {
    CHECK(e.body() == victim);
    CHECK(e.field() == "v");
    CHECK(e.step() == 5);
  }
  CHECK(w.steps_queued() == 5);
  w.syncHost();
  const std::vector<float> after = host_state(set);
  REQUIRE(after.size() == before.size());
  std::size_t changed = 0;
  for (std::size_t k = 0; k < after.size(); ++k) changed += !(after[k] == before[k]);
  CHECK(changed == 1);  // the poisoned component alone
  CHECK(std::isnan(set[victim].v[0]));
}
