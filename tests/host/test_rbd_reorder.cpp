// Spatial order (World::reorder_bodies, SpatialOrder) on the CPU backend: the
// bodies move to a Morton order on the device, contacts' bodies sit closer in
// memory, and nothing a user sees changes: the BodySet's indices name the same
// bodies, the steps after a reorder are the steps without it (to the order of
// the sums), the warm start follows its pairs, and additions, removals and
// errors speak of BodySet indices.
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

template <class W>
std::vector<double> state(W& w, BodySet<double>& set) {
  w.syncHost();
  std::vector<double> x;
  for (const auto& b : set.records()) {
    for (int c = 0; c < 3; ++c) x.push_back(b.pos[c]), x.push_back(b.v[c]), x.push_back(b.w[c]);
    for (int c = 0; c < 4; ++c) x.push_back(b.q[c]);
  }
  return x;
}

double largest_difference(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::fabs(a[i] - b[i]));
  return d;
}

// The mean distance in memory of a contact's two moving bodies.
template <class W>
double mean_contact_spread(W& w) {
  const auto c = w.contacts().view();
  const auto b = w.bodies().view();
  double sum = 0;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (b.moving(c.a[i]) && b.moving(c.b[i])) {
      sum += std::fabs(double(c.a[i]) - double(c.b[i]));
      ++pairs;
    }
  REQUIRE(pairs > 0);
  return sum / double(pairs);
}

}  // namespace

TEST_CASE("spatial order: moving bodies along a Morton curve, fixed ones after them in their order, contacts closer",
          "[rbd_reorder]") {
  BodySet<double> set = shuffled(pile<double>(8, 6));  // 384 spheres on a plane, records shuffled
  set.add_plane({1, 0, 0}, -1), set.add_plane({-1, 0, 0}, -12);
  World<device::cpu, double> w(set, SolverSettings<double>{});
  w.step();
  const double before = mean_contact_spread(w);
  w.reorder_bodies();
  w.step();
  const double after = mean_contact_spread(w);
  INFO("mean slot distance of a contact's bodies: " << before << " before, " << after << " after");
  CHECK(after * 4 < before);
  // The three planes last, in the BodySet's order; every body in exactly one slot.
  const auto& m = w.manager();
  const std::size_t n = set.size();
  std::vector<std::size_t> planes;
  std::vector<int> seen(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    REQUIRE(m.body(m.slot(i)) == i);
    ++seen[m.slot(i)];
    if (set[i].shape == plane) planes.push_back(m.slot(i));
  }
  for (int s : seen) REQUIRE(s == 1);
  REQUIRE(planes.size() == 3);
  CHECK(planes[0] == n - 3);
  CHECK(planes[1] == n - 2);
  CHECK(planes[2] == n - 1);
}

// A World of spheres steps alike in any order of its bodies, to the order of
// the sums (over a few steps: a pile of spheres spreading on a floor is chaotic
// and turns 1e-10 into centimetres within 100 steps). One with boxes, capsules or compounds does not: the narrow phase
// meets a pair in the roles the order gives it (the reference face of a box
// pair is the first body's where both would do), so the same heap with its
// records reversed, no reorder involved, differs by 7.6e-5 m/s after 60 steps.
// There the reorder must keep the indices and the state, and the heap settle alike.
TEST_CASE("reorder_bodies: the BodySet's indices keep their bodies and the steps after it are the steps without it",
          "[rbd_reorder][shapes][compound]") {
  SolverSettings<double> s;
  s.max_iterations = 400, s.check_every = 1, s.tolerance = 1e-8;
  SECTION("spheres: the same steps") {
    BodySet<double> plain_set = shuffled(pile<double>(5, 4));
    BodySet<double> ordered_set = plain_set;
    World<device::cpu, double> plain(plain_set, s), ordered(ordered_set, s);
    plain.advance(100), ordered.advance(100);
    ordered.reorder_bodies();
    CHECK(largest_difference(state(plain, plain_set), state(ordered, ordered_set)) == 0);
    plain.advance(10), ordered.advance(10);
    const double d = largest_difference(state(plain, plain_set), state(ordered, ordered_set));
    INFO("largest difference of a position, velocity or orientation after 10 steps: " << d);
    CHECK(d < 1e-8);
  }
  SECTION("every shape: the same bodies in the same state, and the heap settles alike") {
    BodySet<double> plain_set = shuffled(mixed_heap<double>(4, 3));  // compounds too
    BodySet<double> ordered_set = plain_set;
    World<device::cpu, double> plain(plain_set, SolverSettings<double>{}), ordered(ordered_set, SolverSettings<double>{});
    plain.advance(100), ordered.advance(100);
    ordered.reorder_bodies();
    // Nothing moved: the BodySet reads the same, and body i sits in slot(i).
    CHECK(largest_difference(state(plain, plain_set), state(ordered, ordered_set)) == 0);
    const auto b = ordered.bodies().view();
    for (std::size_t i = 0; i < ordered_set.size(); ++i) {
      const std::size_t k = ordered.manager().slot(i);
      REQUIRE(b.shape[k] == ordered_set[i].shape);
      REQUIRE(b.inv_mass[k] == ordered_set[i].inv_mass);
      for (int c = 0; c < 3; ++c) REQUIRE(b.pos(k, c) == ordered_set[i].pos[c]);
    }
    const auto st0 = plain.step(), st1 = ordered.step();
    CHECK(st1.solver.contacts == st0.solver.contacts);
    plain.advance(400), ordered.advance(400);
    const auto p0 = plain.latest_stats(), p1 = ordered.latest_stats();
    CHECK(p1.max_penetration < 0.01);
    CHECK(p0.max_penetration < 0.01);
    CHECK(double(p1.solver.contacts) == Approx(double(p0.solver.contacts)).epsilon(0.1));
    plain.syncHost(), ordered.syncHost();
    double h0 = 0, h1 = 0;  // the settled heaps' mean heights
    for (std::size_t i = 0; i < plain_set.size(); ++i) h0 += plain_set[i].pos[2], h1 += ordered_set[i].pos[2];
    CHECK(h1 / double(plain_set.size()) == Approx(h0 / double(plain_set.size())).margin(0.02));
  }
}

TEST_CASE("reorder_bodies: the warm start follows its pairs through a reorder (spheres at rest)", "[rbd_reorder]") {
  // One layer of touching spheres on the floor, records shuffled: at rest, so
  // a solve that starts from the last impulses converges at once.
  BodySet<double> plain_set = shuffled(pile<double>(8, 1));
  BodySet<double> ordered_set = plain_set, cold_set = plain_set;
  SolverSettings<double> s;
  s.max_iterations = 1000, s.check_every = 1, s.tolerance = 1e-9, s.warm_start = 1;
  World<device::cpu, double> plain(plain_set, s), ordered(ordered_set, s), cold(cold_set, s);
  plain.advance(50), ordered.advance(50), cold.advance(50);
  ordered.reorder_bodies();
  // The same pile with the warm start forgotten at the reorder: what it would cost.
  SolverSettings<double> forget = s;
  forget.warm_start = 0;
  cold.set_settings(forget);
  const auto st0 = plain.step(), st1 = ordered.step(), st2 = cold.step();
  INFO("iterations after the reorder: " << st1.solver.iterations << ", without it " << st0.solver.iterations
                                        << ", starting cold " << st2.solver.iterations);
  CHECK(st1.solver.contacts == st0.solver.contacts);
  CHECK(std::abs(double(st1.solver.iterations) - double(st0.solver.iterations)) <= 1);
  CHECK(st2.solver.iterations > 5 * st0.solver.iterations);
}

TEST_CASE("reorder_every: added and removed bodies, syncHost and a NaN's error speak of BodySet indices",
          "[rbd_reorder]") {
  BodySet<double> plain_set = shuffled(pile<double>(4, 3));
  BodySet<double> ordered_set = plain_set;
  SolverSettings<double> s;
  s.max_iterations = 200, s.check_every = 1, s.tolerance = 1e-9;
  SolverSettings<double> every = s;
  every.reorder_every = 7;
  World<device::cpu, double> plain(plain_set, s), ordered(ordered_set, every);
  plain.advance(50), ordered.advance(50);
  CHECK(largest_difference(state(plain, plain_set), state(ordered, ordered_set)) < 1e-9);
  // A sphere dropped on top and one taken away, in both.
  for (auto* pair : {&plain_set, &ordered_set}) {
    const std::size_t added = pair->add_sphere({1.5, 1.5, 6}, 0.5, 1);
    (void)added;
  }
  plain.manager().bodyAdded(plain_set.size() - 1), ordered.manager().bodyAdded(ordered_set.size() - 1);
  plain.manager().bodyRemoved(5), ordered.manager().bodyRemoved(5);
  plain.manager().syncDevice(), ordered.manager().syncDevice();
  plain.advance(60), ordered.advance(60);
  CHECK(plain_set[5].status == removed);
  CHECK(ordered_set[5].status == removed);
  const double d = largest_difference(state(plain, plain_set), state(ordered, ordered_set));
  INFO("after an addition and a removal: " << d);
  CHECK(d < 1e-6);
  CHECK(ordered_set.records().back().pos[2] < 5.95);  // the new sphere falls
  // A NaN in the velocity of the BodySet's body 9 (written where it sits on
  // the device, as a kernel would) is named as body 9.
  ordered.bodies().v(ordered.manager().slot(9), 1) = std::nan("");
  try {
    ordered.step();
    FAIL("a NaN velocity was stepped");
  } catch (const NonFiniteStateError& e) {
    CHECK(e.body() == 9);
  }
}

TEST_CASE("reorder_every under advance_unattended: the steps of advance(), reordered at the same steps",
          "[rbd_reorder][unattended]") {
  BodySet<double> attended_set = shuffled(pile<double>(4, 3));
  BodySet<double> unattended_set = attended_set;
  SolverSettings<double> every;
  every.reorder_every = 7;
  World<device::cpu, double> attended(attended_set, every), unattended(unattended_set, every);
  attended.advance(40);
  unattended.advance_unattended(25), unattended.advance_unattended(15);
  CHECK(largest_difference(state(attended, attended_set), state(unattended, unattended_set)) == 0);
  for (std::size_t i = 0; i < attended_set.size(); ++i)
    REQUIRE(unattended.manager().slot(i) == attended.manager().slot(i));
}

TEST_CASE("reorder_bodies, then a compaction of removed bodies: the BodySet's order again, the same bodies",
          "[rbd_reorder]") {
  BodySet<double> plain_set = shuffled(pile<double>(12, 2));  // 288 spheres
  BodySet<double> ordered_set = plain_set;
  SolverSettings<double> s;
  s.max_iterations = 200, s.check_every = 1, s.tolerance = 1e-9;
  World<device::cpu, double> plain(plain_set, s), ordered(ordered_set, s);
  plain.advance(20), ordered.advance(20);
  ordered.reorder_bodies();
  for (auto* w : {&plain, &ordered})
    for (std::size_t i = 1; i <= default_rebuild_threshold; ++i) w->manager().bodyRemoved(i);
  const SyncReport a = plain.manager().syncDevice(), b = ordered.manager().syncDevice();
  REQUIRE(a.rebuilt);
  REQUIRE(b.rebuilt);
  REQUIRE(ordered_set.size() == plain_set.size());
  for (std::size_t i = 0; i < ordered_set.size(); ++i) REQUIRE(ordered.manager().slot(i) == i);
  CHECK(largest_difference(state(plain, plain_set), state(ordered, ordered_set)) == 0);
  plain.advance(10), ordered.advance(10);
  CHECK(largest_difference(state(plain, plain_set), state(ordered, ordered_set)) < 1e-8);
}

namespace {

// A BodyExchange that shares nothing: enough to make a World distributed.
struct NoExchange final : BodyExchange<double> {
  std::vector<double> store;
  VectorD2View<double> sums(std::size_t bodies) override {
    store.resize(6 * bodies);
    return {store.data(), bodies, 6, bodies};
  }
  void combine(std::size_t, stream_t) override {}
  void reduce(double*, ExchangeOp, stream_t) override {}
};

}  // namespace

TEST_CASE("a distributed World keeps its bodies in global-id order: reordering is refused by name", "[rbd_reorder]") {
  BodySet<double> set = pile<double>(2, 1);
  World<device::cpu, double> w(set, SolverSettings<double>{});
  NoExchange exchange;
  w.set_exchange(&exchange);
  CHECK_THROWS_AS(w.reorder_bodies(), UnsupportedError);
  const auto names_reorder_every = [](auto&& f) {
    try {
      f();
      return false;
    } catch (const InvalidArgumentError& e) {
      return std::string(e.what()).find("reorder_every") != std::string::npos;
    }
  };
  SolverSettings<double> every;
  every.reorder_every = 10;
  CHECK(names_reorder_every([&] { w.set_settings(every); }));
  w.set_exchange(nullptr);
  w.set_settings(every);
  CHECK(names_reorder_every([&] { w.set_exchange(&exchange); }));
}
