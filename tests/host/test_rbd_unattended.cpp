// Steps queued with no host wait (World::advance_unattended) on the CPU
// backend: the same bodies, statistics and contacts as advance(); a step
// whose contacts outgrow the list is held and taken again; a body that is not
// finite is reported with its index and the step, and nothing moves.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"
#include "test_rbd_step_checks.hpp"

using namespace rbd_test;

namespace {

template <class W>
std::vector<std::uint64_t> pairs(W& w) {
  auto& c = w.contacts();
  std::vector<std::uint64_t> out;
  for (std::size_t i = 0; i < c.size(); ++i) out.push_back(pair_key(c.a[i], c.b[i]));
  return out;
}

// Closes up the implosion ball: no gravity, a margin of a radius.
SolverSettings<double> ball_settings() {
  SolverSettings<double> s;
  s.gravity[2] = 0;
  s.margin = 0.5;
  s.dt = 0.01;
  return s;
}

// The same to the bit (a deterministic method), else to 1e-9 (atomics,
// whose order of addition OpenMP's threads vary).
void same_state(const std::vector<double>& a, const std::vector<double>& b, bool exact) {
  if (exact) {
    CHECK(a == b);
    return;
  }
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k] == Approx(b[k]).margin(1e-9));
}

template <class Method>
void unattended_equals_advance(bool exact = true) {
  using W = World<device::cpu, double, ConeFriction, Method>;
  auto set_a = pile<double>(3, 3), set_b = set_a;
  W a(set_a, pile_settings()), b(set_b, pile_settings());
  a.advance(30);
  b.advance_unattended(30);
  if (exact) {
    same_stats(a.previous_stats(), b.previous_stats());
    same_stats(a.latest_stats(), b.latest_stats());
  }
  CHECK(a.latest_stats().solver.contacts > 30);
  CHECK(a.latest_stats().solver.contacts == b.latest_stats().solver.contacts);
  CHECK(b.steps_queued() == 30);
  CHECK(b.steps_requeued() == 0);
  same_state(state(a), state(b), exact);
  CHECK(pairs(a) == pairs(b));
  // Attended and unattended steps mix.
  a.advance(5), b.advance_unattended(2), b.advance(1), b.advance_unattended(2);
  same_state(state(a), state(b), exact);
  if (exact) same_stats(a.latest_stats(), b.latest_stats());
}

}  // namespace

TEST_CASE("unattended steps: the same bodies, statistics and contacts as advance()", "[rbd_step][unattended]") {
  SECTION("APGD, gather (the default)") { unattended_equals_advance<AcceleratedJacobi<Gather>>(); }
  SECTION("Jacobi, atomic") { unattended_equals_advance<Jacobi<Atomic>>(false); }
  SECTION("Jacobi, update cache (its passes are counted on the host)") {
    unattended_equals_advance<Jacobi<UpdateCache>>();
  }
  SECTION("coloured Gauss-Seidel (waits as advance() does)") { unattended_equals_advance<ColouredGaussSeidel>(); }
}

TEST_CASE("unattended steps: a step whose contacts outgrow the list is held and taken again",
          "[rbd_step][unattended]") {
  auto set_a = implosion<double>(4, 4.0), set_b = set_a;
  SolverSettings<double> s = ball_settings();
  s.contacts_per_body = 4;  // the ball passes 4 contacts per body in the middle of the run
  World<device::cpu, double> a(set_a, s), b(set_b, s);
  const std::size_t capacity = 4 * set_a.size();
  std::vector<std::size_t> counts;
  for (int i = 0; i < 12; ++i) counts.push_back(a.step().solver.contacts);
  INFO("contacts per step: first " << counts.front() << ", last " << counts.back());
  REQUIRE(counts.front() > 0);
  REQUIRE(counts[3] <= capacity);
  REQUIRE(counts.back() > capacity);
  SECTION("every step unattended") {
    b.advance_unattended(12);
    CHECK(state(a) == state(b));  // finish() settled the steps
    CHECK(b.steps_queued() == 12);
    CHECK(b.steps_requeued() > 0);
    CHECK(pairs(a) == pairs(b));
    same_stats(a.latest_stats(), b.latest_stats());
    same_stats(a.previous_stats(), b.previous_stats());
    CHECK(b.contacts().capacity() >= counts.back());
  }
  SECTION("attended up to the step before the overflow: the held step still starts from their impulses") {
    // The attended steps remember as many impulses as they found, the first
    // unattended step the list's whole capacity: the warm start grows where
    // that step is held, and keeps the impulses it carries when queued again.
    const auto over = std::find_if(counts.begin(), counts.end(), [&](std::size_t c) { return c > capacity; });
    const std::size_t attended = std::size_t(over - counts.begin());
    REQUIRE(attended > 1);
    b.advance(attended);
    b.advance_unattended(counts.size() - attended);
    CHECK(state(a) == state(b));
    CHECK(b.steps_requeued() > 0);
    same_stats(a.latest_stats(), b.latest_stats());
  }
}

TEST_CASE("unattended steps: room for the contacts a scene holds, set from the start, holds no step",
          "[rbd_step][unattended]") {
  auto set_a = implosion<double>(4, 4.0), set_b = set_a, set_c = set_a;
  const std::size_t n = set_a.size();
  World<device::cpu, double> a(set_a, ball_settings());
  std::size_t most = 0;
  for (int i = 0; i < 12; ++i) most = std::max(most, a.step().solver.contacts);
  REQUIRE(most > ContactSettings<double>{}.contacts_per_body * n);  // the default room runs short
  SolverSettings<double> s = ball_settings();
  s.contacts_per_body = most / n + 1;
  World<device::cpu, double> b(set_b, s);
  b.advance_unattended(12);
  CHECK(b.steps_requeued() == 0);
  CHECK(state(a) == state(b));
  CHECK(b.contacts().capacity() == s.contacts_per_body * n);
  World<device::cpu, double> c(set_c, ball_settings());  // the default room: the list grows on the way
  c.advance_unattended(12);
  CHECK(c.contacts().capacity() >= most);
  CHECK(state(a) == state(c));
  s.contacts_per_body = 0;
  CHECK(refused_naming([&] { s.validate(); }, "contacts_per_body"));
}

TEST_CASE("unattended steps: a NaN or infinity names the body and the step, and nothing moves from there",
          "[rbd_step][unattended]") {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    auto set = pile<double>(3, 2, 0.5, 0.05);
    World<device::cpu, double> w(set, pile_settings());
    w.advance_unattended(7);
    auto& b = w.bodies();
    const std::size_t victim = 11;
    b.v(victim, 0) = bad;
    const std::vector<double> before = state(w);
    w.advance_unattended(5);  // queues; nothing is reported yet
    INFO("value " << bad);
    try {
      w.finish();
      FAIL("the steps ran with a non-finite state");
    } catch (const NonFiniteStateError& e) {
      CHECK(e.body() == victim);
      CHECK(e.field() == std::string("v"));
      CHECK(e.step() == 7);
    }
    CHECK(w.steps_queued() == 7);
    const std::vector<double> after = state(w);
    REQUIRE(after.size() == before.size());
    for (std::size_t k = 0; k < after.size(); ++k)
      CHECK((after[k] == before[k] || (std::isnan(after[k]) && std::isnan(before[k]))));
    // Repaired, the World steps on, unattended.
    b.v(victim, 0) = 0.0;
    CHECK_NOTHROW(w.advance_unattended(3));
    CHECK_NOTHROW(w.finish());
    CHECK(w.steps_queued() == 10);
    CHECK(w.latest_stats().solver.contacts > 0);
  }
}
