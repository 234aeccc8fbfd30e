// Every solver method on the CPU backend: contact colouring, the isotropic
// friction cone (a sphere sliding in any direction), impulses inside their cone,
// and a column of alternating light and heavy spheres, for Jacobi, coloured
// Gauss-Seidel, APGD, substepping and APGD with CG steps (cone friction only).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"
#include "../../bench/shared_pile.hpp"

using namespace rbd_test;

TEST_CASE("contact colouring: no colour holds two contacts of one moving body, and it is deterministic",
          "[rbd_methods]") {
  auto set = pile<double>(4, 4);  // 64 spheres, up to 12 contacts each, and the floor
  BodyManager<device::cpu, double> m(set);
  m.syncDeviceFull();
  Contacts<device::cpu, double, Frictionless> c;
  CollisionDetection<device::cpu, double> cd;
  cd.detect(m.device(), c, 0.02);
  REQUIRE(c.size() > 200);
  const auto b = m.device().view();
  ContactColouring<device::cpu> col;
  col.build(b, c.view());
  REQUIRE(col.colours() >= 6);  // a sphere inside the pile touches many others
  CHECK(col.colours() <= 30);
  std::vector<std::uint32_t> seen(c.size(), 0);
  std::size_t floor_contacts = 0;
  for (std::size_t k = 0; k < col.colours(); ++k) {
    std::set<std::uint32_t> bodies;
    for (std::size_t p = col.offset(k); p < col.offset(k + 1); ++p) {
      const std::uint32_t i = col.order()[p];
      REQUIRE(i < c.size());
      ++seen[i];
      REQUIRE(col.colour()[i] == k);
      for (std::uint32_t body : {c.a(i), c.b(i)}) {
        if (!b.moving(body)) {
          ++floor_contacts;
          continue;
        }
        REQUIRE(bodies.insert(body).second);  // no moving body twice in one colour
      }
    }
  }
  CHECK(floor_contacts >= 16);
  for (std::uint32_t n : seen) REQUIRE(n == 1);  // every contact in exactly one colour
  ContactColouring<device::cpu> again;
  again.build(b, c.view());
  REQUIRE(again.colours() == col.colours());
  for (std::size_t p = 0; p < c.size(); ++p) REQUIRE(again.order()[p] == col.order()[p]);
  CHECK_FALSE(col.kept());
  const std::size_t needed = col.rounds_needed();
  CHECK(needed > 0);
  CHECK(needed <= col.rounds());
  const std::vector<std::uint32_t> first(col.order(), col.order() + c.size());
  // Built again on the same pairs, it keeps its colours.
  col.build(b, c.view());
  CHECK(col.kept());
  REQUIRE(col.colours() == again.colours());
  for (std::size_t p = 0; p < c.size(); ++p) REQUIRE(col.order()[p] == first[p]);
  // A body that stops moving changes what conflicts: coloured anew. Moving
  // again, the pairs are the first build's: coloured anew, running the rounds
  // the last build needed and a quarter more in one batch, and alike.
  std::uint32_t inner = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (b.moving(c.a(i)) && b.moving(c.b(i))) inner = c.a(i);
  b.status[inner] = fixed;
  col.build(b, c.view());
  CHECK_FALSE(col.kept());
  const std::size_t needed_fixed = col.rounds_needed();
  b.status[inner] = active;
  col.build(b, c.view());
  CHECK_FALSE(col.kept());
  CHECK(col.rounds() == needed_fixed + needed_fixed / 4 + 2);
  CHECK(col.rounds_needed() == needed);
  REQUIRE(col.colours() == again.colours());
  for (std::size_t p = 0; p < c.size(); ++p) REQUIRE(col.order()[p] == first[p]);
}

TEST_CASE("the colouring's sort: pairs ordered by key, equal keys kept in their order", "[rbd_methods]") {
  // Keys as a colouring leaves them: colours below 9, and a pair's later points marked `follows`.
  const std::size_t n = 200;
  std::vector<std::uint32_t> keys(n), values(n), keys_out(n), values_out(n);
  for (std::size_t i = 0; i < n; ++i) {
    keys[i] = i % 7 == 3 ? rbd::detail::follows : std::uint32_t((i * 5 + i / 11) % 9);
    values[i] = std::uint32_t(i);
  }
  rbd::detail::DeviceAlgorithms<device::cpu> algorithms;
  algorithms.stable_sort_pairs(keys.data(), keys_out.data(), values.data(), values_out.data(), n, 32, stream_t{});
  for (std::size_t i = 0; i < n; ++i) REQUIRE(keys_out[i] == keys[values_out[i]]);  // each pair moved whole
  for (std::size_t i = 1; i < n; ++i) {
    REQUIRE(keys_out[i - 1] <= keys_out[i]);
    if (keys_out[i - 1] == keys_out[i]) REQUIRE(values_out[i - 1] < values_out[i]);  // stable
  }
  std::vector<std::uint32_t> seen(values_out);
  std::sort(seen.begin(), seen.end());
  for (std::size_t i = 0; i < n; ++i) REQUIRE(seen[i] == i);  // every pair once
}

TEST_CASE("contact colouring colours body pairs: a box pair's points share one colour, and a sweep hands one thread the whole pair",
          "[rbd_methods][shapes]") {
  BodySet<double> set = gpusolve::bench::box_pyramid<double>(8);  // 36 boxes on a floor, four points per face
  BodyManager<device::cpu, double> m(set);
  m.syncDeviceFull();
  Contacts<device::cpu, double, ConeFriction> c;
  CollisionDetection<device::cpu, double> cd;
  cd.detect(m.device(), c, 0.1);
  const auto b = m.device().view();
  const auto cv = c.view();
  std::size_t pairs = 0, most_points = 0;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (cv.opens_pair(i)) {
      ++pairs;
      std::size_t k = 1;
      while (i + k < c.size() && cv.same_pair(i, i + k)) ++k;
      most_points = std::max(most_points, k);
    }
  REQUIRE(most_points == 4);
  REQUIRE(c.size() >= 3 * pairs);
  ContactColouring<device::cpu> col;
  col.build(b, cv);
  // A box touches at most two below, two beside and two above: six moving
  // neighbours; the greedy colouring in hashed order takes 9 here (point by
  // point it took four times as many: each point of a pair needs its own colour).
  CHECK(col.colours() >= 3);
  CHECK(col.colours() <= 10);
  REQUIRE(col.offset(col.colours()) == pairs);
  std::vector<std::uint32_t> swept;  // the contacts one sweep visits, in its order
  const rbd::detail::ColourView view = col.view();
  for (std::size_t k = 0; k < col.colours(); ++k) {
    std::set<std::uint32_t> bodies;
    for (std::size_t p = col.offset(k); p < col.offset(k + 1); ++p) {
      const std::uint32_t i = col.order()[p];
      REQUIRE(cv.opens_pair(i));
      for (std::uint32_t body : {c.a(i), c.b(i)})
        if (b.moving(body)) REQUIRE(bodies.insert(body).second);  // no moving body twice in one colour
    }
    const auto record = [&](std::size_t first, std::size_t end) {
      REQUIRE(end > first);
      for (std::size_t p = first; p < end; ++p) {
        REQUIRE(cv.same_pair(first, p));  // the whole pair, and nothing past it
        swept.push_back(std::uint32_t(p));
      }
      REQUIRE((end == c.size() || !cv.same_pair(first, end)));
    };
    const rbd::detail::InColour<decltype(record), decltype(cv)> in{record, cv, view, k};
    for (std::size_t j = 0; j < view.widest; ++j) in(j);
  }
  std::vector<std::uint32_t> sorted = swept;
  std::sort(sorted.begin(), sorted.end());
  REQUIRE(sorted.size() == c.size());  // every point once
  for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == i);
}

TEST_CASE("contact grouping: each moving body's entries in entry order, the fixed bodies' behind them",
          "[rbd_methods]") {
  auto set = pile<double>(4, 4);
  BodyManager<device::cpu, double> m(set);
  m.syncDeviceFull();
  Contacts<device::cpu, double, Frictionless> found;
  CollisionDetection<device::cpu, double> cd;
  cd.detect(m.device(), found, 0.02);
  const std::size_t nc = found.size();
  REQUIRE(nc > 200);
  // The same contacts in reverse order: the grouping must not rely on detection's (a, b) order.
  Contacts<device::cpu, double, Frictionless> c;
  c.resize(nc);
  const auto fv = found.view();
  const auto cv = c.view();
  for (std::size_t i = 0; i < nc; ++i) cv.a[i] = fv.a[nc - 1 - i], cv.b[i] = fv.b[nc - 1 - i];
  const auto b = m.device().view();
  const std::size_t nb = b.size();
  for (int build = 0; build < 3; ++build) {  // atomic arrival order may differ per build; the result may not
    ContactGrouping<device::cpu> grouping;
    grouping.build(b, cv);
    const auto g = grouping.view();
    std::vector<std::vector<std::uint32_t>> expected(nb);
    std::vector<std::uint32_t> fixed;
    for (std::uint32_t e = 0; e < 2 * nc; ++e) {
      const std::uint32_t k = (e & 1) ? cv.b[e / 2] : cv.a[e / 2];
      (b.moving(k) ? expected[k] : fixed).push_back(e);
    }
    REQUIRE(fixed.size() >= 16);  // the floor's
    for (std::size_t k = 0; k < nb; ++k) {
      REQUIRE(g.start[k + 1] - g.start[k] == expected[k].size());
      for (std::uint32_t r = 0; r < expected[k].size(); ++r) {
        const std::uint32_t p = g.start[k] + r;
        REQUIRE(g.entry[p] == expected[k][r]);
        REQUIRE(g.rank[p] == r);
        REQUIRE(g.slot[expected[k][r]] == p);
      }
    }
    REQUIRE(g.start[nb] == 2 * nc - fixed.size());
    std::vector<std::uint32_t> tail(&g.entry[g.start[nb]], &g.entry[0] + 2 * nc);
    std::sort(tail.begin(), tail.end());
    REQUIRE(tail == fixed);
    for (std::uint32_t e : fixed) REQUIRE(g.entry[g.slot[e]] == e);
  }
}

namespace {

// A sphere (radius 0.5) launched without spin at v0 along angle theta on the
// plane z = 0. Friction mu decelerates it and spins it up until the contact
// point stops slipping at t* = 2 v0 / (7 mu g); from then on it rolls at 5/7 v0.
struct Sliding {
  double t_stop = -1;                 // first time the contact point's slip fell below 1e-3 v0
  double v_along = 0, v_across = 0;   // velocity after rolling for a while
};

template <class Model, class Method>
Sliding slide(double theta, double v0, double mu) {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  const double r = 0.5;
  set.add_sphere({0, 0, r}, r, 1.0);
  set[1].v = {v0 * std::cos(theta), v0 * std::sin(theta), 0};
  SolverSettings<double> s;
  s.dt = 5e-4, s.margin = 0.01, s.tolerance = 1e-10, s.friction = mu;
  World<device::cpu, double, Model, Method> w(set, s);
  Sliding out;
  const double t_star = 2 * v0 / (7 * mu * g);
  const int steps = int(1.5 * t_star / s.dt);
  for (int i = 1; i <= steps; ++i) {
    REQUIRE(w.step().solver.contacts == 1);
    auto& b = w.bodies();
    // Slip: velocity of the contact point (0, 0, -r) from the centre, v + w x (0, 0, -r).
    const double sx = b.v(1, 0) - r * b.w(1, 1), sy = b.v(1, 1) + r * b.w(1, 0);
    if (out.t_stop < 0 && std::hypot(sx, sy) < 1e-3 * v0) out.t_stop = i * s.dt;
  }
  w.syncHost();
  out.v_along = set[1].v[0] * std::cos(theta) + set[1].v[1] * std::sin(theta);
  out.v_across = -set[1].v[0] * std::sin(theta) + set[1].v[1] * std::cos(theta);
  return out;
}

template <class Method>
void check_cone_sliding() {
  const double v0 = 2.0, mu = 0.3;
  const double t_star = 2 * v0 / (7 * mu * g);
  for (double deg : {0.0, 22.5, 45.0, 67.5}) {
    INFO("direction " << deg << " degrees, method " << Method::name);
    const Sliding s = slide<ConeFriction, Method>(deg * M_PI / 180, v0, mu);
    CHECK(s.t_stop == Approx(t_star).epsilon(0.02));
    CHECK(s.v_along == Approx(5.0 / 7.0 * v0).epsilon(0.01));
    CHECK(std::fabs(s.v_across) < 1e-6 * v0);
  }
}

}  // namespace

TEST_CASE("cone friction: a sphere sliding in any direction stops slipping at 2 v0 / (7 mu g), then rolls at 5/7 v0",
          "[rbd_methods]") {
  check_cone_sliding<Jacobi<Gather>>();
  check_cone_sliding<ColouredGaussSeidel>();
  check_cone_sliding<AcceleratedJacobi<Gather>>();
  check_cone_sliding<Substepping<>>();
  check_cone_sliding<AcceleratedCG>();
}

TEST_CASE("the pyramid's friction depends on the direction of sliding (the cone's does not)", "[rbd_methods]") {
  const double v0 = 2.0, mu = 0.3;
  const double t_star = 2 * v0 / (7 * mu * g);
  // Along a tangent axis the pyramid is exact; on its diagonal the force reaches
  // sqrt(2) mu N and the sphere stops slipping sqrt(2) times too early.
  const Sliding axis = slide<PyramidFriction, ColouredGaussSeidel>(0.0, v0, mu);
  const Sliding diagonal = slide<PyramidFriction, ColouredGaussSeidel>(M_PI / 4, v0, mu);
  CHECK(axis.t_stop == Approx(t_star).epsilon(0.02));
  CHECK(diagonal.t_stop == Approx(t_star / std::sqrt(2.0)).epsilon(0.03));
}

namespace {

template <class Method>
void check_impulses_in_cone() {
  auto set = pile<double>(3, 2, 0.5, 0.01);
  for (std::size_t i = 1; i < set.size(); ++i) set[i].v = {0.3 * double(i % 3) - 0.3, 0.2, -1.0};
  SolverSettings<double> s;
  s.dt = 0.005, s.margin = 0.02, s.friction = 0.3;
  World<device::cpu, double, ConeFriction, Method> w(set, s);
  std::size_t checked = 0, on_rim = 0;
  for (int step = 0; step < 60; ++step) {
    w.step();
    auto& c = w.contacts();
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double xn = c.x(i, 0), lim = c.mu(i) * xn, xt = std::hypot(c.x(i, 1), c.x(i, 2));
      REQUIRE(xn >= 0);
      REQUIRE(xt <= lim * (1 + 1e-12) + 1e-15);
      checked += xn > 0;
      on_rim += xn > 0 && xt > 0.999 * lim;
    }
  }
  CHECK(checked > 100);
  CHECK(on_rim > 0);  // some contacts slide: the rim of the cone was reached
}

}  // namespace

TEST_CASE("every method keeps each impulse inside its friction cone", "[rbd_methods]") {
  check_impulses_in_cone<Jacobi<Gather>>();
  check_impulses_in_cone<ColouredGaussSeidel>();
  check_impulses_in_cone<AcceleratedJacobi<Gather>>();
  check_impulses_in_cone<Substepping<>>();
  check_impulses_in_cone<AcceleratedCG>();
}

namespace {

// Ten spheres (radius 0.5) stacked on the floor, masses alternating 1 and
// `ratio` from the bottom: heavy on light is what makes the iteration slow (the
// light sphere's contacts see the heavy one's weight only through many
// iterations). Returns how far the top sphere sank below its resting height and
// the largest penetration over `steps` steps, relative to the radius.
struct ColumnRun {
  double sank = 0, penetration = 0, iterations = 0;  // iterations: mean per step
  double settled = 0;                                 // mean iterations per step over the last third
};

template <class Method>
ColumnRun column(double ratio, int steps, std::size_t check_every = SolverSettings<double>{}.check_every) {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  const double r = 0.5;
  for (int k = 0; k < 10; ++k) set.add_sphere({0, 0, r + 2 * r * k}, r, k % 2 ? ratio : 1.0);
  SolverSettings<double> s;
  s.margin = 0.05, s.max_iterations = 2000;  // converged solves: the test is whether it stands
  s.check_every = check_every;
  World<device::cpu, double, ConeFriction, Method> w(set, s);
  ColumnRun out;
  const int late = steps - 2 * steps / 3;
  for (int i = 0; i < steps; ++i) {
    const auto st = w.step();
    REQUIRE(st.solver.status != SolverStatus::diverged);
    out.penetration = std::fmax(out.penetration, st.max_penetration);
    out.iterations += double(st.solver.total_iterations) / steps;
    if (i >= steps - late) out.settled += double(st.solver.total_iterations) / late;
  }
  w.syncHost();
  out.sank = (r + 18 * r - set[10].pos[2]) / r;
  return out;
}

}  // namespace

TEST_CASE("a column of spheres with masses 1 and 1000 stands under every method", "[rbd_methods]") {
  for (double ratio : {1.0, 1000.0}) {
    const ColumnRun runs[5] = {column<Jacobi<Gather>>(ratio, 400), column<ColouredGaussSeidel>(ratio, 400),
                               column<AcceleratedJacobi<Gather>>(ratio, 400), column<Substepping<>>(ratio, 400),
                               column<AcceleratedCG>(ratio, 400)};
    for (const ColumnRun& c : runs) {
      INFO("mass ratio " << ratio << ": sank " << c.sank << ", penetration " << c.penetration << ", "
                         << c.iterations << " iterations per step");
      CHECK(std::fabs(c.sank) < 0.02);
      CHECK(c.penetration < 0.005);
    }
    // Momentum is what the heavy column needs: Jacobi and Gauss-Seidel run into
    // the 2 000-iteration cap, APGD converges in a few hundred (about 190 here),
    // four substeps of APGD in about 130 all together.
    if (ratio == 1000.0) {
      CHECK(runs[2].iterations < 400);
      CHECK(runs[3].iterations < 400);
      CHECK(runs[4].iterations < 400);
      CHECK(runs[0].iterations > 1000);
    }
  }
}

TEST_CASE("APGD with CG steps settles the 1:1000 column in a few iterations per step, where APGD needs hundreds",
          "[rbd_methods]") {
  // The shared column (bench/shared_pile.hpp's mass_column, here at radius 0.5)
  // at tolerance 5e-3, checked every 10 iterations, capped at 2 000. Measured
  // over the last third of 600 steps: AcceleratedCG 10.0 iterations per step
  // (each solve converges at its first check), APGD 186.
  const ColumnRun cg = column<AcceleratedCG>(1000.0, 600, 10);
  const ColumnRun apgd = column<AcceleratedJacobi<Gather>>(1000.0, 600, 10);
  INFO("AcceleratedCG " << cg.settled << ", APGD " << apgd.settled << " iterations per step");
  CHECK(cg.settled <= 100);
  CHECK(apgd.settled > 100);  // what makes the column a test of the method
  CHECK(std::fabs(cg.sank) < 0.02);
  CHECK(cg.penetration < 0.005);
}

TEST_CASE("APGD with CG steps converges to APGD's velocities on a small pile with cone friction", "[rbd_methods]") {
  // With friction the impulses of a pile need not be unique; the velocities
  // (the minimiser of a convex QP in J^T x) are. Both methods run to a tight
  // tolerance, three steps from the same start; measured: 1.4e-8 m/s apart.
  auto set = pile<double>(2, 2);
  for (std::size_t i = 1; i < set.size(); ++i) set[i].v = {0.2 * double(i % 3) - 0.2, 0.1, -0.5};
  SolverSettings<double> s;
  s.margin = 0.02, s.friction = 0.4, s.tolerance = 1e-9, s.max_iterations = 40000, s.check_every = 10;
  World<device::cpu, double, ConeFriction, AcceleratedJacobi<Gather>> ref(set, s);
  World<device::cpu, double, ConeFriction, AcceleratedCG> cg(set, s);
  for (int i = 0; i < 3; ++i) {
    REQUIRE(ref.step().solver.status == SolverStatus::converged);
    const auto st = cg.step();
    REQUIRE(st.solver.status == SolverStatus::converged);
    REQUIRE(st.solver.contacts >= 10);
    CHECK(st.solver.iterations > 0);
  }
  const auto v_ref = velocities(ref.bodies());
  double fastest = 0;
  for (double v : v_ref) fastest = std::fmax(fastest, std::fabs(v));
  REQUIRE(fastest > 0.05);  // a comparison of motion, not of rest
  CHECK(max_abs_diff(velocities(cg.bodies()), v_ref) < 1e-7);
}

TEST_CASE("substepping: one substep is the inner method's step, four stay close to it", "[rbd_methods]") {
  // Four spheres on the floor and one in their hollow, pushing them apart.
  auto set = pile<double>(2, 1);
  set.add_sphere({0.5, 0.5, 0.5 + std::sqrt(0.5)}, 0.5, 1.0);
  SolverSettings<double> s;
  s.margin = 0.02, s.tolerance = 1e-10, s.max_iterations = 40000, s.check_every = 10, s.friction = 0.4;
  SolverSettings<double> one_substep = s;
  one_substep.substeps = 1;
  World<device::cpu, double, ConeFriction, Jacobi<Gather>> ref(set, s);
  World<device::cpu, double, ConeFriction, Substepping<Jacobi<Gather>>> same(set, one_substep);
  World<device::cpu, double, ConeFriction, Substepping<>> four(set, s);
  for (int i = 0; i < 3; ++i) {
    REQUIRE(ref.step().solver.status == SolverStatus::converged);
    REQUIRE(same.step().solver.status == SolverStatus::converged);
    const auto st = four.step();
    REQUIRE(st.solver.status == SolverStatus::converged);
    CHECK(st.solver.iterations > 0);
  }
  const auto v_ref = velocities(ref.bodies());
  double fastest = 0;
  for (double v : v_ref) fastest = std::fmax(fastest, std::fabs(v));
  REQUIRE(fastest > 0.03);  // the lower spheres roll apart: a comparison of motion, not of rest
  CHECK(max_abs_diff(velocities(same.bodies()), v_ref) < 1e-8);
  // Four substeps integrate the same motion more finely: within a fifth of it.
  CHECK(max_abs_diff(velocities(four.bodies()), v_ref) < 0.2 * fastest);
}

TEST_CASE("contact colouring past 64 colours: a body with 80 contacts needs 80", "[rbd_methods]") {
  // 80 small spheres touching one large one: every contact shares the large
  // body, so each needs a colour of its own, beyond the first-fit mask's 64.
  // Past 64 the colour is 64 + the round it was picked in, so some numbers stay
  // empty; an empty colour costs an empty launch.
  BodySet<double> set;
  set.add_sphere({0, 0, 0}, 10.0, 100.0);
  for (int k = 0; k < 80; ++k) {
    const double z = -1 + (2 * k + 1) / 80.0, rho = std::sqrt(1 - z * z), phi = 2.399963 * k;  // golden angle
    const double R = 10.0 + 0.2 - 1e-3;
    set.add_sphere({R * rho * std::cos(phi), R * rho * std::sin(phi), R * z}, 0.2, 1.0);
  }
  BodyManager<device::cpu, double> m(set);
  m.syncDeviceFull();
  Contacts<device::cpu, double, Frictionless> c;
  CollisionDetection<device::cpu, double> cd;
  cd.detect(m.device(), c, 0.01);
  REQUIRE(c.size() == 80);
  ContactColouring<device::cpu> col;
  col.build(m.device().view(), c.view());
  REQUIRE(col.colours() >= 80);
  std::size_t used = 0;
  for (std::size_t k = 0; k < col.colours(); ++k) {
    const std::size_t size = col.offset(k + 1) - col.offset(k);
    REQUIRE(size <= 1);
    used += size;
  }
  CHECK(used == 80);
  CHECK(col.offset(col.colours()) == 80);
}

TEST_CASE("every method returns at once, converged, when there are no contacts", "[rbd_methods]") {
  auto check = [](auto method) {
    using Method = decltype(method);
    BodySet<double> set;
    set.add_plane({0, 0, 1}, 0);
    set.add_sphere({0, 0, 5}, 0.5, 1.0);
    World<device::cpu, double, ConeFriction, Method> w(set, SolverSettings<double>{});
    const auto st = w.step();
    CHECK(st.solver.contacts == 0);
    CHECK(st.solver.status == SolverStatus::converged);
    w.syncHost();
    CHECK(set[1].v[2] == Approx(-9.81 * 0.0025));  // gravity applied once, by World or by the substeps
  };
  check(Jacobi<Gather>{});
  check(AcceleratedJacobi<Gather>{});
  check(ColouredGaussSeidel{});
  check(Substepping<>{});
  check(AcceleratedCG{});
}
