// The queued time step on the CPU backend: steps queued with advance() equal
// steps taken one by one, statistics read late equal statistics read at once,
// a NaN in a body's state stops the step naming the body and the step, and the
// collision lists grow without dropping a contact.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "test_rbd_collision_scene.hpp"
#include "test_rbd_scenes.hpp"
#include "test_rbd_step_checks.hpp"

using namespace rbd_test;

namespace {

}  // namespace

TEST_CASE("queued steps: statistics read one step late equal those read at once", "[rbd_step]") {
  auto set_a = pile<double>(3, 3), set_b = set_a;
  World<device::cpu, double> a(set_a, pile_settings()), b(set_b, pile_settings());
  CHECK(b.latest_stats().solver.contacts == 0);  // nothing queued yet: zero statistics
  std::vector<StepStats<double>> at_once;
  for (int i = 0; i < 40; ++i) at_once.push_back(a.step());
  b.advance(1);
  for (int i = 1; i < 40; ++i) {
    b.advance(1);
    INFO("step " << i - 1);
    same_stats(b.previous_stats(), at_once[std::size_t(i - 1)]);
  }
  same_stats(b.latest_stats(), at_once.back());
  CHECK(b.steps_queued() == 40);
  CHECK(at_once.back().solver.contacts > 30);
  CHECK(at_once.back().max_penetration > 0);
  CHECK(state(a) == state(b));
}

TEST_CASE("queued steps: advance(N) moves the bodies exactly as N calls of step()", "[rbd_step]") {
  auto set_a = pile<double>(3, 2, 0.5, 0.05), set_b = set_a;
  World<device::cpu, double> a(set_a, pile_settings()), b(set_b, pile_settings());
  for (int i = 0; i < 25; ++i) a.step();
  b.advance(25);
  CHECK(state(a) == state(b));
  same_stats(a.latest_stats(), b.latest_stats());
}

TEST_CASE("queued steps: the GPU's loop settings (graphs, persistent) leave the CPU backend's loop as it is",
          "[rbd_step]") {
  auto set_a = pile<double>(3, 2), set_b = set_a;
  SolverSettings<double> s = pile_settings();
  s.check_every = 7;  // runs of iterations between checks, the last one short
  s.graphs = s.detection_graph = true, s.persistent_max_contacts = ~std::size_t(0);
  World<device::cpu, double> a(set_a, s);
  s.graphs = s.detection_graph = false, s.persistent_max_contacts = 0;
  World<device::cpu, double> b(set_b, s);
  a.advance(20), b.advance(20);
  CHECK(state(a) == state(b));
  CHECK(a.latest_stats().solver.iterations == b.latest_stats().solver.iterations);
}

TEST_CASE("phase timing: measured when asked, zero otherwise", "[rbd_step]") {
  auto set = pile<double>(3, 2);
  World<device::cpu, double> w(set, pile_settings());
  const auto off = w.step();
  CHECK(off.time_detection == 0);
  CHECK(off.time_solve == 0);
  w.set_phase_timing(true);
  const auto on = w.step();
  CHECK(on.time_detection > 0);
  CHECK(on.time_solve > 0);
  CHECK(on.time_integration >= 0);
}

TEST_CASE("a NaN or infinity in one body's state names the body and the step, and moves nothing",
          "[rbd_step]") {
  const char* const fields[] = {"pos", "q", "v", "w"};
  for (int f = 0; f < 4; ++f)
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
      auto set = pile<double>(3, 2, 0.5, 0.05);
      World<device::cpu, double> w(set, pile_settings());
      w.advance(7);
      auto& b = w.bodies();
      const std::size_t victim = 11;
      if (f == 0) b.pos(victim, 1) = bad;
      if (f == 1) b.q(victim, 2) = bad;
      if (f == 2) b.v(victim, 0) = bad;
      if (f == 3) b.w(victim, 2) = bad;
      const std::vector<double> before = state(w);
      INFO("field " << fields[f] << ", value " << bad);
      try {
        w.step();
        FAIL("the step ran with a non-finite state");
      } catch (const NonFiniteStateError& e) {
        CHECK(e.body() == victim);
        CHECK(e.field() == fields[f]);
        CHECK(e.step() == 7);
        const std::string what = e.what();
        CHECK(what.find("body 11") != std::string::npos);
        CHECK(what.find("step 7") != std::string::npos);
      }
      const std::vector<double> after = state(w);
      REQUIRE(after.size() == before.size());
      for (std::size_t k = 0; k < after.size(); ++k)  // NaN == NaN fails: compare the bits' meaning
        CHECK((after[k] == before[k] || (std::isnan(after[k]) && std::isnan(before[k]))));
      CHECK(w.steps_queued() == 7);
      CHECK(w.latest_stats().solver.contacts > 0);  // the last good step's statistics are kept
      // Repaired, the World steps on.
      if (f == 0) b.pos(victim, 1) = 1.0;
      if (f == 1) b.q(victim, 2) = 0.0;
      if (f == 2) b.v(victim, 0) = 0.0;
      if (f == 3) b.w(victim, 2) = 0.0;
      CHECK_NOTHROW(w.step());
      CHECK(w.steps_queued() == 8);
    }
}

TEST_CASE("collision detection grows its pair and contact lists and drops none", "[rbd_step][collision]") {
  // 60 spheres of radius 0.5 within 0.45 of each other, all sinking into a
  // plane: 1770 pairs and 1830 contacts, far past the 4 per body reserved at first.
  BodySet<float> s;
  const std::size_t spheres = 60;
  for (std::size_t i = 0; i < spheres; ++i)
    s.add_sphere({0.05f * float(i % 5), 0.05f * float((i / 5) % 4), 0.05f + 0.1f * float(i / 20)}, 0.5f, 1.f);
  s.add_plane({0, 0, 1}, 0.f);
  const auto expected = brute_force_pairs(s, 0.f);
  REQUIRE(expected.size() > 4 * s.size());
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  UniformGrid<device::cpu> grid;
  const std::size_t n = grid.find_pairs(m.device(), 0.f);
  CHECK(std::vector<std::uint64_t>(grid.pairs(), grid.pairs() + n) == expected);
  CollisionDetection<device::cpu> cd;
  Contacts<device::cpu, float, Frictionless> c;
  const std::size_t nc = cd.detect(m.device(), c, 0.f);
  CHECK(nc == expected.size() + spheres);
  CHECK(c.size() == nc);
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < nc; ++i) keys.push_back(pair_key(c.a[i], c.b[i]));
  CHECK(std::is_sorted(keys.begin(), keys.end()));
  CHECK(std::adjacent_find(keys.begin(), keys.end()) == keys.end());
  // A second detection reuses the grown lists and finds the same.
  CHECK(cd.detect(m.device(), c, 0.f) == nc);
}

TEST_CASE("the solver's runs of iterations end at each residual check and at the last iteration", "[rbd_step]") {
  SolverSettings<double> s;
  s.check_every = 7, s.max_iterations = 50;
  SolverStats<double> stats;
  const ConvergenceMonitor<double> m(s, stats);
  CHECK(m.next_check(1) == 7);
  CHECK(m.next_check(7) == 7);
  CHECK(m.next_check(8) == 14);
  CHECK(m.next_check(43) == 49);
  CHECK(m.next_check(50) == 50);  // the last iteration always checks, off the grid of 7
  for (std::size_t it = 1; it <= 50; ++it) CHECK(m.checks(m.next_check(it)));
  CHECK(ConvergenceRule<double>(s).max_checks() == 8);  // 7, 14, ..., 49 and 50
  // The defaults (check_every 0): a check every 10 of the 50 iterations.
  CHECK(ConvergenceRule<double>(SolverSettings<double>{}).next_check(1) == 10);
  CHECK(ConvergenceRule<double>(SolverSettings<double>{}).next_check(41) == 50);
  CHECK(ConvergenceRule<double>(SolverSettings<double>{}).max_checks() == 5);
}

TEST_CASE("the convergence rule stops where the host's monitor stops and records the same checks", "[rbd_step]") {
  SolverSettings<double> s;
  s.check_every = 4, s.max_iterations = 40, s.tolerance = 1e-3;
  // Falling, then growing for three checks past ten times the smallest: diverged at iteration 24.
  const std::vector<double> residuals = {1.0, 0.5, 0.01, 0.02, 0.05, 0.2, 0.1};
  SolverStats<double> monitored;
  ConvergenceMonitor<double> m(s, monitored);
  ConvergenceRule<double> rule(s);
  std::vector<double> seen;
  for (std::size_t k = 0, it = 0; k < residuals.size(); ++k) {
    it = rule.next_check(it + 1);
    seen.push_back(residuals[k]);
    const bool stops = rule.stop(it, residuals[k]);
    CHECK(stops == m.stop(it, residuals[k]));
    if (stops) break;
  }
  CHECK(rule.status == SolverStatus::diverged);
  CHECK(rule.iterations == 24);
  SolverStats<double> recorded;
  record_checks(rule, seen, recorded);
  CHECK(recorded.status == monitored.status);
  CHECK(recorded.iterations == monitored.iterations);
  CHECK(recorded.residuals == monitored.residuals);
  CHECK(recorded.checked_at == monitored.checked_at);
  CHECK(recorded.checked_at == std::vector<std::size_t>{4, 8, 12, 16, 20, 24});
  // Converged below the tolerance; and at the cap, off the grid of checks.
  ConvergenceRule<double> converging(s);
  CHECK_FALSE(converging.stop(4, 0.5));
  CHECK(converging.stop(8, 1e-4));
  CHECK(converging.status == SolverStatus::converged);
  s.max_iterations = 10;
  ConvergenceRule<double> capped(s);
  CHECK_FALSE(capped.stop(8, 0.5));
  CHECK(capped.next_check(9) == 10);
  CHECK(capped.stop(10, 0.4));
  CHECK(capped.status == SolverStatus::max_iterations);
}

TEST_CASE("the default checks: every 10 iterations, but only the last after a check far from the tolerance",
          "[rbd_step]") {
  SolverSettings<double> s;  // check_every 0, 50 iterations, tolerance 5e-3
  const double far = far_from_tolerance * s.tolerance;
  ConvergenceRule<double> near(s);
  CHECK(near.next_check(1) == 10);
  CHECK_FALSE(near.stop(10, 0.99 * far));  // within reach: every 10 as before
  CHECK(near.next_check(11) == 20);
  CHECK(near.checks(20));
  ConvergenceRule<double> off(s);
  CHECK_FALSE(off.stop(10, 1.01 * far));  // a pile's solve: the next check is the last
  CHECK(off.next_check(11) == 50);
  CHECK_FALSE(off.checks(20));
  CHECK(off.checks(50));
  CHECK(off.stop(50, 1e-3));
  CHECK(off.status == SolverStatus::converged);
  // A schedule the settings name is kept whatever the residual.
  s.check_every = 10;
  ConvergenceRule<double> named(s);
  CHECK_FALSE(named.stop(10, 100 * far));
  CHECK(named.next_check(11) == 20);
  // The host's monitor and the device's record agree on where the checks fell.
  s.check_every = 0;
  const std::vector<double> residuals = {0.5 * far, 2 * far, 0.01};
  SolverStats<double> monitored;
  ConvergenceMonitor<double> m(s, monitored);
  ConvergenceRule<double> rule(s);
  for (std::size_t k = 0, it = 0; k < residuals.size(); ++k) {
    it = rule.next_check(it + 1);
    CHECK(rule.stop(it, residuals[k]) == m.stop(it, residuals[k]));
  }
  CHECK(monitored.checked_at == std::vector<std::size_t>{10, 20, 50});
  SolverStats<double> recorded;
  record_checks(rule, residuals, recorded);
  CHECK(recorded.checked_at == monitored.checked_at);
  CHECK(recorded.status == SolverStatus::max_iterations);
}
