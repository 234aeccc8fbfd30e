// The contact solver on the CPU backend: strategies agree with each other and with
// Gauss-Seidel, impulses stay in their pyramid, divergence and bad settings are reported.
#include <cmath>
#include <limits>
#include <string>

#include "catch_compat.hpp"
#include "gpusolve/rbd/pgs.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

using Store = BodyManager<device::cpu, double>;

SolverSettings<double> tight() {
  SolverSettings<double> s;
  s.dt = 0.01;
  s.margin = 0.02;
  s.omega = 0.5;
  s.tolerance = 1e-11;
  s.max_iterations = 20000;
  s.check_every = 10;
  return s;
}

template <class Model, class Strategy>
SolverStats<double> jacobi(Bodies<device::cpu, double>& b, Contacts<device::cpu, double, Model>& c,
                           const SolverSettings<double>& s) {
  prepare_solve(b, c, s);
  return JacobiSolver<device::cpu, double, Model, Strategy>().solve(b, c, s);
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidArgumentError& e) {
    return e.what();
  }
  return "no InvalidArgumentError";
}

}  // namespace

TEST_CASE("Jacobi (every strategy) and Gauss-Seidel converge to the same impulses", "[rbd_solver]") {
  auto set = pile<double>(2, 2);  // 8 spheres, frictionless: a unique solution
  const SolverSettings<double> s = tight();
  Store gs_store(set);
  gs_store.syncDeviceFull();
  Contacts<device::cpu, double, Frictionless> gs_c;
  prepare_solve(gs_store.device(), gs_c, s);
  SolverSettings<double> gs = s;
  gs.omega = 1;
  const auto gst = solve_gauss_seidel(gs_store.device(), gs_c, gs);
  REQUIRE(gst.status == SolverStatus::converged);
  REQUIRE(gs_c.size() >= 10);
  const auto x_ref = impulses(gs_c);
  const auto v_ref = velocities(gs_store.device());
  double largest = 0;
  for (double x : x_ref) largest = std::fmax(largest, x);
  REQUIRE(largest > 0.05);  // the pile carries weight: the comparison is not 0 == 0

  auto check = [&](auto strategy) {
    using Strategy = decltype(strategy);
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, Frictionless> c;
    const auto stats = jacobi<Frictionless, Strategy>(st.device(), c, s);
    REQUIRE(stats.status == SolverStatus::converged);
    REQUIRE(stats.iterations > 1);
    CHECK(max_abs_diff(impulses(c), x_ref) < 1e-7 * largest);
    CHECK(max_abs_diff(velocities(st.device()), v_ref) < 1e-8);
  };
  check(UpdateCache{});
  check(Atomic{});
  check(Gather{});
}

TEST_CASE("update-cache, atomic and gather accumulation give the same velocities", "[rbd_solver]") {
  auto set = pile<double>(3, 3);
  SolverSettings<double> s = tight();
  s.max_iterations = 300;  // same number of iterations for all
  s.divergence_checks = 0;
  s.friction = 0.4;
  Store a(set), b(set), g(set);
  a.syncDeviceFull(), b.syncDeviceFull(), g.syncDeviceFull();
  Contacts<device::cpu, double, PyramidFriction> ca, cb, cg;
  const auto sa = jacobi<PyramidFriction, UpdateCache>(a.device(), ca, s);
  jacobi<PyramidFriction, Atomic>(b.device(), cb, s);
  jacobi<PyramidFriction, Gather>(g.device(), cg, s);
  REQUIRE(sa.contacts > 50);
  REQUIRE(sa.reduction_passes >= 3);  // a sphere of the pile has 5 to 8 contacts
  const auto va = velocities(a.device());
  CHECK(max_abs_diff(va, velocities(b.device())) < 1e-12);
  CHECK(max_abs_diff(va, velocities(g.device())) < 1e-12);
  CHECK(max_abs_diff(impulses(ca), impulses(cg)) < 1e-12);
}

TEST_CASE("every contact impulse lies inside its friction pyramid", "[rbd_solver]") {
  auto set = pile<double>(3, 2, 0.5, 0.01);
  for (std::size_t i = 1; i < set.size(); ++i) set[i].v = {0.3 * double(i % 3) - 0.3, 0.2, -1.0};
  SolverSettings<double> s;
  s.dt = 0.005, s.margin = 0.02, s.friction = 0.3, s.omega = 0.4;
  World<device::cpu, double, PyramidFriction, UpdateCache> w(set, s);
  std::size_t checked = 0, sticking = 0;
  for (int step = 0; step < 60; ++step) {
    w.step();
    auto& c = w.contacts();
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double xn = c.x(i, 0), lim = c.mu(i) * xn + 1e-12;
      REQUIRE(c.mu(i) == Approx(0.3));
      REQUIRE(xn >= 0);
      REQUIRE(std::fabs(c.x(i, 1)) <= lim);
      REQUIRE(std::fabs(c.x(i, 2)) <= lim);
      checked += xn > 0;
      sticking += xn > 0 && std::fabs(c.x(i, 1)) < 0.99 * lim && std::fabs(c.x(i, 2)) < 0.99 * lim;
    }
  }
  CHECK(checked > 100);
  CHECK(sticking < checked);  // some contacts slide: the pyramid's faces were reached
}

TEST_CASE("divergence is detected: omega = 1 on a dense pile, and NaN velocities", "[rbd_solver]") {
  auto set = pile<double>(3, 3);
  SolverSettings<double> s = tight();
  s.max_iterations = 2000;
  s.omega = 1.0;  // thesis 5.2: undamped Jacobi diverges on such piles
  {
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, PyramidFriction> c;
    const auto r = jacobi<PyramidFriction, Gather>(st.device(), c, s);
    CHECK(r.status == SolverStatus::diverged);
    CHECK(r.iterations < 200);
    CHECK(r.residual() > 1e3 * r.residuals.front() / 10);
  }
  {
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, PyramidFriction> c;
    SolverSettings<double> t = s;
    t.throw_on_divergence = true;
    CHECK_THROWS_AS((jacobi<PyramidFriction, UpdateCache>(st.device(), c, t)), DivergenceError);
  }
  {  // the same pile converges with under-relaxation
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, PyramidFriction> c;
    SolverSettings<double> t = s;
    t.omega = 0.5;
    t.tolerance = 1e-6;
    t.max_iterations = 5000;
    CHECK(jacobi<PyramidFriction, Gather>(st.device(), c, t).status == SolverStatus::converged);
  }
  {  // a NaN velocity is reported at the first check, not swallowed by the projection
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, Frictionless> c;
    SolverSettings<double> t = s;
    t.omega = 0.5;
    prepare_solve(st.device(), c, t);
    st.device().v(5, 2) = std::numeric_limits<double>::quiet_NaN();
    const auto r = JacobiSolver<device::cpu, double, Frictionless, Atomic>().solve(st.device(), c, t);
    CHECK(r.status == SolverStatus::diverged);
    CHECK(r.iterations == t.check_every);
    CHECK(std::isinf(r.residual()));
  }
}

TEST_CASE("bad solver settings give InvalidArgumentError naming the field", "[rbd_solver]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  auto with = [&](auto change) {
    SolverSettings<double> s;
    change(s);
    return error_of([&] { World<device::cpu, double> w(set, s); });
  };
  CHECK(with([](auto& s) { s.dt = 0; }).find("`dt`") != std::string::npos);
  CHECK(with([](auto& s) { s.dt = -1; }).find("`dt`") != std::string::npos);
  CHECK(with([](auto& s) { s.omega = 0; }).find("`omega`") != std::string::npos);
  CHECK(with([](auto& s) { s.omega = 2; }).find("`omega`") != std::string::npos);
  CHECK(with([](auto& s) { s.tolerance = 0; }).find("`tolerance`") != std::string::npos);
  CHECK(with([](auto& s) { s.friction = -0.1; }).find("`friction`") != std::string::npos);
  CHECK(with([](auto& s) { s.margin = -0.1; }).find("`margin`") != std::string::npos);
  CHECK(with([](auto& s) { s.correction = 0; }).find("`correction`") != std::string::npos);
  CHECK(with([](auto& s) { s.correction = 1.5; }).find("`correction`") != std::string::npos);
  CHECK(with([](auto& s) { s.check_every = 0; }).find("`check_every`") != std::string::npos);
  CHECK(with([](auto&) {}).find("no InvalidArgumentError") != std::string::npos);
  World<device::cpu, double> w(set, SolverSettings<double>{});
  SolverSettings<double> bad;
  bad.omega = 2.5;
  CHECK_THROWS_AS(w.set_settings(bad), InvalidArgumentError);
  CHECK(w.settings().omega == SolverSettings<double>{}.omega);  // unchanged
}
