// Warm starting (warm_start.hpp, SolverSettings::warm_start) on the CPU backend:
// fewer iterations for the same impulses, carried impulses re-expressed in the
// new contact frame, a diverging warm start retried cold, the setting validated.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

SolverSettings<double> resting(double warm) {
  SolverSettings<double> s;
  s.dt = 0.005, s.margin = 0.01, s.omega = 0.5, s.tolerance = 1e-8, s.check_every = 1;
  s.warm_start = warm;
  return s;
}

}  // namespace

TEST_CASE("warm start: a resting sphere converges in fewer iterations to the same impulse", "[rbd_warm_start]") {
  BodySet<double> set_off, set_on;
  for (BodySet<double>* set : {&set_off, &set_on}) {
    set->add_plane({0, 0, 1}, 0);
    set->add_sphere({0, 0, 0.5}, 0.5, 1.0);
  }
  World<device::cpu, double> off(set_off, resting(0)), on(set_on, resting(1));
  for (int i = 0; i < 50; ++i) {
    const auto a = off.step(), b = on.step();
    REQUIRE(a.solver.contacts == 1);
    REQUIRE(b.solver.contacts == 1);
    REQUIRE(a.solver.status == SolverStatus::converged);
    REQUIRE(b.solver.status == SolverStatus::converged);
    if (i == 0) {
      CHECK(b.solver.iterations == a.solver.iterations);  // nothing to carry yet
    } else {
      CHECK(b.solver.iterations < a.solver.iterations);
    }
    // The solves stop at residual 1e-8 m/s; the impulse of a 1 kg body agrees to that.
    CHECK(std::fabs(on.contacts().x(0, 0) - off.contacts().x(0, 0)) < 1e-7);
    CHECK(on.contacts().x(0, 0) > 0);
  }
}

TEST_CASE("warm start: a settling pile needs fewer iterations, penetration stays bounded", "[rbd_warm_start]") {
  auto run = [](double warm) {
    auto set = pile<double>(3, 3, 0.5, 0.05);  // 27 spheres dropped by a little, boxed in by walls
    const double L = 2 * 1.05 + 0.525 + 0.51;     // past the far row's surface (pile(): d = 2r + gap)
    set.add_plane({1, 0, 0}, -0.51), set.add_plane({-1, 0, 0}, -L);
    set.add_plane({0, 1, 0}, -0.51), set.add_plane({0, -1, 0}, -L);
    SolverSettings<double> s;
    s.check_every = 10, s.warm_start = warm, s.max_iterations = 2000;  // counts iterations to convergence
    World<device::cpu, double> w(set, s);
    double iterations = 0, worst = 0;
    for (int i = 0; i < 200; ++i) {
      const auto st = w.step();
      REQUIRE(st.solver.status == SolverStatus::converged);
      iterations += double(st.solver.total_iterations);
      worst = std::fmax(worst, st.max_penetration);
    }
    return std::pair<double, double>(iterations / 200, worst);
  };
  const auto off = run(0), on = run(0.8);
  CHECK(on.first < off.first);
  CHECK(on.second < 0.05);  // the thesis's bound for the well
  CHECK(on.second < 2 * off.second + 1e-3);
}

TEST_CASE("warm start: a carried frictional impulse keeps its world direction in the new frame", "[rbd_warm_start]") {
  using C = Contacts<device::cpu, double, PyramidFriction>;
  C before(1), after(2);
  const double r[3] = {0, 0, 0};
  const double n0[3] = {0.3, 0.4, std::sqrt(1 - 0.25)};
  const double n1[3] = {0.45, 0.35, std::sqrt(1 - 0.45 * 0.45 - 0.35 * 0.35)};  // turned: tangents swap axes
  before.view().set(0, 4, 0, n0, r, r, 0.0, 0.5);
  after.view().set(0, 2, 0, n1, r, r, 0.0, 0.5);  // a new pair
  after.view().set(1, 4, 0, n1, r, r, 0.0, 0.5);  // the persisting pair
  before.x(0, 0) = 2.0, before.x(0, 1) = 0.3, before.x(0, 2) = -0.2;
  REQUIRE(std::fabs(before.t(0, 0) - after.t(1, 0)) > 0.5);  // the frames differ a lot
  WarmStart<device::cpu, double, PyramidFriction> ws;
  ws.remember(before.view());
  CHECK(ws.remembered() == 1);
  Bodies<device::cpu, double> bodies(5);  // their poses matter only to friction anchors, off here
  ws.carry(bodies.view(), after.view(), 0.5, 0.01);
  for (std::size_t k = 0; k < 3; ++k) CHECK(after.x(0, k) == 0.0);
  for (std::size_t k = 0; k < 3; ++k) {
    double p_before = 0, p_after = 0;
    for (std::size_t row = 0; row < 3; ++row) {
      const C::VecD2& q0 = row == 0 ? before.n : row == 1 ? before.t : before.o;
      const C::VecD2& q1 = row == 0 ? after.n : row == 1 ? after.t : after.o;
      p_before += q0(0, k) * before.x(0, row);
      p_after += q1(1, k) * after.x(1, row);
    }
    CHECK(p_after == Approx(0.5 * p_before).margin(1e-12));  // inside the pyramid: nothing projected
  }
  ws.forget();
  ws.carry(bodies.view(), after.view(), 1.0, 0.01);
  for (std::size_t k = 0; k < 3; ++k) CHECK(after.x(1, k) == 0.0);
}

TEST_CASE("warm start: a diverging warm-started solve is retried from zero impulses", "[rbd_warm_start]") {
  SolverSettings<double> s;
  s.dt = 0.01, s.margin = 0.02, s.omega = 1.0, s.tolerance = 1e-9, s.max_iterations = 3000;
  s.check_every = 10, s.divergence_checks = 3, s.max_retries = 3;
  auto solve = [&](bool warm) {
    auto set = pile<double>(3, 3);
    BodyManager<device::cpu, double> m(set);
    m.syncDeviceFull();
    Contacts<device::cpu, double, PyramidFriction> c;
    prepare_solve(m.device(), c, s);
    for (std::size_t i = 0; i < c.size(); ++i) c.x(i, 0) = 0.5, c.x(i, 1) = c.x(i, 2) = 0.0;
    const auto st = JacobiSolver<device::cpu, double, PyramidFriction>().solve(m.device(), c, s, {}, warm);
    return std::pair(st, velocities(m.device()));
  };
  const auto cold = solve(false), warm = solve(true);
  REQUIRE(cold.first.retries >= 1);
  REQUIRE(warm.first.retries == cold.first.retries);
  REQUIRE(warm.first.status != SolverStatus::diverged);
  CHECK(warm.first.iterations == cold.first.iterations);
  CHECK(max_abs_diff(warm.second, cold.second) == 0.0);  // the retries were the same cold solve
}

TEST_CASE("warm start: the pair search from a guess finds what a binary search finds", "[rbd_warm_start]") {
  std::mt19937 gen(3);
  for (std::size_t count : {0, 1, 2, 3, 7, 64, 1000}) {
    std::vector<std::uint64_t> keys(count);
    std::uniform_int_distribution<std::uint64_t> gap(1, 5);
    std::uint64_t k = 10;
    for (auto& key : keys) key = k += gap(gen);
    std::vector<std::uint64_t> probes = {0, 5, 10, k, k + 1, k + 100};
    for (std::uint64_t q = 5; q < k + 3; q += 1 + q % 7) probes.push_back(q);
    for (std::uint64_t key : probes) {
      const std::size_t expected = std::size_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin());
      for (std::size_t guess = 0; guess < count + 3; guess += 1 + guess / 3)
        REQUIRE(rbd::detail::lower_bound_near(keys.data(), count, key, guess) == expected);
    }
  }
}

TEST_CASE("warm_start outside [0, 1] gives InvalidArgumentError naming it", "[rbd_warm_start]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  for (double bad : {-0.1, 1.5, double(NAN)}) {
    SolverSettings<double> s;
    s.warm_start = bad;
    std::string what = "no InvalidArgumentError";
    try {
      World<device::cpu, double> w(set, s);
    } catch (const InvalidArgumentError& e) {
      what = e.what();
    }
    CHECK(what.find("`warm_start`") != std::string::npos);
  }
  for (double good : {0.0, 0.8, 1.0}) {
    SolverSettings<double> s;
    s.warm_start = good;
    CHECK_NOTHROW(s.validate());
  }
}
