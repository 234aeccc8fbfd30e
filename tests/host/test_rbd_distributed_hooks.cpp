// What a World offers a distributed world (rbd/distributed/), checked on one
// rank of the CPU backend: shadows (BodyStatus::shadow) move but meet only
// active bodies; a solve through a BodyExchange that adds nothing is the solve
// without one (for Gauss-Seidel, but for rounding), with one combine per iteration; the remembered contacts,
// renumbered, keep the warm start; a method that does not run distributed says
// so; the check of a rank's own bodies where they live (OwnedBodiesCheck); a
// rank's neighbourhood of cells (RankGrid) at any number of ranks.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/distributed/owned_bodies_check.hpp"
#include "test_local_method.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// A BodyExchange of one rank: the sums and reductions stay as they are; it
// counts its calls.
template <class T>
struct CountingExchange final : BodyExchange<T> {
  std::size_t combines = 0, reductions = 0, largest = 0;
  std::vector<T> store;
  VectorD2View<T> sums(std::size_t bodies) override {
    store.resize(6 * bodies);
    return {store.data(), bodies, 6, bodies};
  }
  void combine(std::size_t bodies, stream_t) override {
    ++combines;
    largest = bodies > largest ? bodies : largest;
  }
  void reduce(T*, ExchangeOp, stream_t) override { ++reductions; }
};

// A small pile: 12 spheres in a box of planes, dropped by a little.
BodySet<double> small_pile() {
  auto set = pile<double>(2, 3, 0.5, 0.05);
  const double L = 2 * 1.05 + 0.525 + 0.51;
  set.add_plane({1, 0, 0}, -0.51), set.add_plane({-1, 0, 0}, -L);
  set.add_plane({0, 1, 0}, -0.51), set.add_plane({0, -1, 0}, -L);
  return set;
}

}  // namespace

TEST_CASE("distributed hooks: a shadow moves but meets only active bodies", "[rbd_distributed]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);                               // 0
  const std::size_t a = set.add_sphere({0, 0, 0.5}, 0.5, 1);   // 1: active, on the floor
  const std::size_t b = set.add_sphere({0.9, 0, 0.5}, 0.5, 1);  // 2: shadow, touching a and the floor
  const std::size_t c = set.add_sphere({1.8, 0, 0.5}, 0.5, 1);  // 3: shadow, touching b and the floor
  set[b].status = shadow, set[c].status = shadow;
  SolverSettings<double> s;
  s.margin = 0.01;
  World<device::cpu, double> w(set, s);
  w.step();
  auto& contacts = w.contacts();
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::size_t k = 0; k < contacts.size(); ++k) pairs.insert({contacts.a(k), contacts.b(k)});
  // a with the floor and a with b: never b with c, nor a shadow with the floor.
  CHECK(pairs == std::set<std::pair<std::uint32_t, std::uint32_t>>{{std::uint32_t(a), 0u}, {std::uint32_t(a), std::uint32_t(b)}});
  // The shadows move: c falls freely (nothing holds it), b is pushed by a only.
  w.syncHost();
  CHECK(set[c].v[2] == Approx(-9.81 * s.dt).epsilon(1e-9));
  CHECK(set[b].pos[2] < 0.5);
}

TEST_CASE("distributed hooks: an exchange that adds nothing gives the solve without one", "[rbd_distributed]") {
  auto run = [](auto method, bool exchanging, CountingExchange<double>& ex) {
    auto set = small_pile();
    SolverSettings<double> s;
    s.max_iterations = 30, s.check_every = 10;
    World<device::cpu, double, ConeFriction, decltype(method)> w(set, s);
    if (exchanging) w.set_exchange(&ex);
    std::size_t iterations = 0;
    for (int i = 0; i < 40; ++i) iterations += w.step().solver.total_iterations;
    return std::make_pair(positions(w, set), iterations);
  };
  CountingExchange<double> none, jacobi, apgd;
  const auto [x_jacobi, it_jacobi] = run(Jacobi<Gather>{}, false, none);
  const auto [y_jacobi, jt_jacobi] = run(Jacobi<Gather>{}, true, jacobi);
  CHECK(y_jacobi == x_jacobi);
  CHECK(jt_jacobi == it_jacobi);
  const auto [x_apgd, it_apgd] = run(AcceleratedJacobi<Gather>{}, false, none);
  const auto [y_apgd, jt_apgd] = run(AcceleratedJacobi<Gather>{}, true, apgd);
  CHECK(y_apgd == x_apgd);
  // One combine per iteration, and one for the warm start of each step that carries impulses.
  CHECK(jacobi.combines >= it_jacobi);
  CHECK(jacobi.combines <= it_jacobi + 40);
  CHECK(jacobi.largest == small_pile().size());
  CHECK(jacobi.reductions > 0);  // the residual checks
  CHECK(apgd.reductions > jacobi.reductions);  // and the momentum's sums
  CHECK(none.combines == 0);
  CountingExchange<double> cg;
  const auto [x_cg, it_cg] = run(AcceleratedCG{}, false, none);
  const auto [y_cg, jt_cg] = run(AcceleratedCG{}, true, cg);
  CHECK(y_cg == x_cg);
  CHECK(jt_cg == it_cg);
  CHECK(cg.combines >= it_cg);  // the direction's body sums, each iteration
  CHECK(cg.reductions > 5 * it_cg);  // its sums, step bound and residual checks
  // Gauss-Seidel adds a sweep's changes to the velocities it started from:
  // the same solve but for the rounding of (after - before) + before.
  CountingExchange<double> gs;
  const auto [x_gs, it_gs] = run(ColouredGaussSeidel{}, false, none);
  const auto [y_gs, jt_gs] = run(ColouredGaussSeidel{}, true, gs);
  REQUIRE(y_gs.size() == x_gs.size());
  for (std::size_t i = 0; i < x_gs.size(); ++i) CHECK(y_gs[i] == Approx(x_gs[i]).margin(1e-12));
  CHECK(jt_gs == it_gs);
  CHECK(gs.combines >= it_gs);  // one per sweep, and one for each warm start
  CHECK(gs.combines <= it_gs + 40);
  CHECK(gs.reductions > 0);
  // Atomic's sums, where an exchange combines them, in iterations that are not
  // rotated: the same solve but for the order of the atomic additions.
  CountingExchange<double> atomic;
  const auto [x_atomic, it_atomic] = run(Jacobi<Atomic>{}, false, none);
  const auto [y_atomic, jt_atomic] = run(Jacobi<Atomic>{}, true, atomic);
  REQUIRE(y_atomic.size() == x_atomic.size());
  for (std::size_t i = 0; i < x_atomic.size(); ++i) CHECK(y_atomic[i] == Approx(x_atomic[i]).margin(1e-12));
  CHECK(jt_atomic == it_atomic);
  CHECK(atomic.combines >= it_atomic);
  CHECK(atomic.combines <= it_atomic + 40);
  CHECK(none.combines == 0);
  // A rank without contacts still takes part in every exchange of a solve.
  BodySet<double> alone;
  alone.add_sphere({0, 0, 5}, 0.5, 1.0);
  SolverSettings<double> once;  // one check, at the cap: the counting exchange reduces this rank's residual alone
  once.check_every = once.max_iterations;
  World<device::cpu, double, ConeFriction, ColouredGaussSeidel> idle(alone, once);
  CountingExchange<double> idle_ex;
  idle.set_exchange(&idle_ex);
  REQUIRE(idle.step().solver.contacts == 0);
  CHECK(idle_ex.combines == once.max_iterations + 1);  // a sweep each, and the warm start's
  CHECK(idle_ex.reductions > 0);
}

TEST_CASE("distributed hooks: a method that does not run distributed says so", "[rbd_distributed]") {
  auto set = small_pile();
  CountingExchange<double> ex;
  World<device::cpu, double, ConeFriction, LocalJacobi> local(set, SolverSettings<double>{});
  CHECK_THROWS_AS(local.set_exchange(&ex), UnsupportedError);
  local.set_exchange(nullptr);  // none is always fine
  CHECK(local.step().solver.contacts > 0);
}

TEST_CASE("distributed hooks: remembered contacts, renumbered, keep the warm start", "[rbd_distributed]") {
  // Two copies of one settling pile, solved short of convergence (so the
  // impulses carried matter); after 10 steps the second gains a far-away
  // sphere in front of its bodies (every index moves up by one), and its
  // remembered contacts are renumbered. Its next steps repeat the first's;
  // without the renumbering they do not.
  SolverSettings<double> s;
  s.max_iterations = 4, s.check_every = 4;
  auto run = [&](bool renumber) {
    auto reference = small_pile(), moved = small_pile();
    World<device::cpu, double> w_ref(reference, s), w(moved, s);
    w_ref.advance(10), w.advance(10);
    w.syncHost();
    auto records = moved.records();
    BodySet<double> far;
    far.add_fixed_sphere({100, 100, 100}, 0.5);
    records.insert(records.begin(), far[0]);
    moved.records() = records;
    w.manager().syncDeviceFull();
    if (renumber) {
      RememberedContacts<double> kept = w.remembered_contacts();
      REQUIRE(!kept.keys.empty());
      for (std::uint64_t& key : kept.keys) key = pair_key(pair_a(key) + 1, pair_b(key) + 1);
      w.remember(kept);
    }
    w_ref.advance(5), w.advance(5);
    const auto x_ref = positions(w_ref, reference);
    auto x = positions(w, moved);
    x.erase(x.begin(), x.begin() + 3);
    double worst = 0;
    for (std::size_t k = 0; k < x.size(); ++k) worst = std::fmax(worst, std::fabs(x[k] - x_ref[k]));
    return worst;
  };
  CHECK(run(true) < 1e-12);
  CHECK(run(false) > 1e-6);
}

TEST_CASE("distributed hooks: the check of a rank's own bodies finds those that must move, and their figures",
          "[rbd_distributed]") {
  // Rank 1 of two cells split at x = 2; shadows reach a body's bound plus 0.6.
  const RankGrid<double> grid({2, 1, 1}, {0, 0, 0}, {4, 1, 1}, 1.1);
  const int rank = 1;
  const double reach = 0.6;
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);                                  // fixed: not counted
  const std::size_t a = set.add_sphere({3, 0, 0.5}, 0.5, 2);    // 1.0 from cell 0: its shadow is there
  const std::size_t b = set.add_sphere({3.5, 0, 0.5}, 0.5, 1);  // 1.5 from cell 0: no shadow
  const std::size_t c = set.add_sphere({1, 0, 0.5}, 0.5, 1);    // rank 0's body: a shadow here, not counted
  set[c].status = shadow;
  set[a].v = {1, 2, 0}, set[a].w = {0, 0, 3};
  set[b].v = {-1, 0, 0};
  set[c].v = {5, 5, 5};
  const std::vector<std::uint64_t> shadowed{0, 1, 0, 0};  // a: held by rank 0
  // The check of the bodies in a World, after `change` to them there, with a skin.
  auto check = [&](const std::vector<std::uint64_t>& at, auto&& change, double skin = 0) {
    BodySet<double> copy = set;
    World<device::cpu, double> w(copy, SolverSettings<double>{});
    change(w.bodies());
    OwnedBodiesCheck<device::cpu, double> owned;
    owned.shadowed_at(at);
    return owned.run(w.bodies().view(), grid, rank, reach, skin);
  };
  const auto as_is = [](auto&) {};
  const OwnedBodies here = check(shadowed, as_is);
  CHECK(here.to_move == 0);
  CHECK(here.count == 2);
  CHECK(here.momentum[0] == Approx(2 * 1 - 1));
  CHECK(here.momentum[1] == Approx(2 * 2));
  CHECK(here.momentum[2] == 0);
  // 1/2 m v^2 of both, and 1/2 (2/5 m r^2) w^2 of a.
  CHECK(here.kinetic_energy == Approx(0.5 * 2 * 5 + 0.5 * 0.4 * 2 * 0.25 * 9 + 0.5 * 1 * 1));
  // A shadow due where there is none moves it; one held where none is due
  // stays (its contacts are still found once, by the lower owner).
  CHECK(check({0, 0, 0, 0}, as_is).to_move == 1);
  CHECK(check({0, 1, 1, 0}, as_is).to_move == 0);
  // A body that crossed into rank 0's cell (its shadow bit as it would be
  // there: only the owner differs); one whose state is not finite.
  CHECK(check({0, 1, 1, 0}, [&](auto& bodies) { bodies.pos(b, 0) = 1.9; }).to_move == 1);
  CHECK(check(shadowed, [&](auto& bodies) { bodies.w(b, 1) = std::nan(""); }).to_move == 1);
  CHECK(check(shadowed, [&](auto& bodies) { bodies.w(c, 1) = std::nan(""); }).to_move == 0);  // rank 0 checks its own
  // With a skin of 0.2 a body stays until it is more than 0.2 past its cell
  // (b held by rank 0, as a skin's wider shadows would have it) ...
  CHECK(check({0, 1, 1, 0}, [&](auto& bodies) { bodies.pos(b, 0) = 1.9; }, 0.2).to_move == 0);
  CHECK(check({0, 1, 1, 0}, [&](auto& bodies) { bodies.pos(b, 0) = 1.7; }, 0.2).to_move == 1);
  // ... and until it comes within its reach and the skin of a rank without
  // its shadow: b at 1.25 from cell 0 needs one there (0.5 + 0.6 + 0.2).
  CHECK(check(shadowed, [&](auto& bodies) { bodies.pos(b, 0) = 3.25; }, 0.2).to_move == 1);
  CHECK(check(shadowed, [&](auto& bodies) { bodies.pos(b, 0) = 3.25; }).to_move == 0);
  CHECK(check({0, 1, 1, 0}, [&](auto& bodies) { bodies.pos(b, 0) = 3.25; }, 0.2).to_move == 0);
}

TEST_CASE("distributed hooks: a rank's neighbourhood holds every lower rank within reach, at any number of ranks",
          "[rbd_distributed]") {
  // Grids of up to 240 ranks, cells narrower and wider than the reach: the
  // ranks that ranks_within names for a point in a rank's cell (through
  // neighbour()) are exactly the lower ranks whose cells, outer ones reaching
  // to infinity, lie within the reach, found here by testing every rank.
  struct Case {
    std::array<int, 3> dims;
    double reach;
  };
  const std::array<double, 3> lo{-10, 0, 1}, hi{30, 16, 7};
  std::mt19937 rng(3);
  for (const Case& g : {Case{{10, 8, 3}, 1.5}, Case{{10, 8, 1}, 2.5}, Case{{40, 1, 1}, 2.5}, Case{{3, 2, 1}, 50}}) {
    const RankGrid<double> grid(g.dims, lo, hi, g.reach);
    const int ranks = grid.ranks();
    auto cell_edge = [&](int a, int c, bool upper) {
      const double w = (hi[a] - lo[a]) / g.dims[a], inf = std::numeric_limits<double>::infinity();
      if (upper) return c == g.dims[a] - 1 ? inf : lo[a] + (c + 1) * w;
      return c == 0 ? -inf : lo[a] + c * w;
    };
    auto cell = [&](int r) {
      return std::array<int, 3>{r % g.dims[0], (r / g.dims[0]) % g.dims[1], r / (g.dims[0] * g.dims[1])};
    };
    int named = 0;
    for (int trial = 0; trial < 400; ++trial) {
      const int rank = std::uniform_int_distribution<int>(0, ranks - 1)(rng);
      std::array<double, 3> p;
      for (int a = 0; a < 3; ++a) {  // a point in rank's cell, now and then outside the box
        const double l = std::fmax(cell_edge(a, cell(rank)[a], false), lo[a] - 3);
        const double u = std::fmin(cell_edge(a, cell(rank)[a], true), hi[a] + 3);
        p[a] = std::uniform_real_distribution<double>(l, u)(rng);
      }
      REQUIRE(grid.owner(p) == rank);
      const double reach = std::uniform_real_distribution<double>(0, g.reach)(rng);
      std::set<int> expected, found;
      for (int r = 0; r < rank; ++r) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
          const double d = std::fmax(0.0, std::fmax(cell_edge(a, cell(r)[a], false) - p[a], p[a] - cell_edge(a, cell(r)[a], true)));
          d2 += d * d;
        }
        if (d2 <= reach * reach) expected.insert(r);
      }
      const std::uint64_t bits = grid.ranks_within(p, reach, rank);
      for (int bit = 0; bit < 64; ++bit)
        if (bits >> bit & 1u) found.insert(grid.neighbour(rank, bit));
      INFO("dims " << g.dims[0] << " x " << g.dims[1] << " x " << g.dims[2] << ", rank " << rank << ", reach " << reach);
      CHECK(found == expected);
      named += int(found.size());
    }
    CHECK(named > 0);  // the cases do name neighbours
  }
  // A reach across more than 64 cells is refused, naming the cells.
  CHECK_THROWS_AS((RankGrid<double>({20, 20, 1}, lo, hi, 5.0)), UnsupportedError);
}
