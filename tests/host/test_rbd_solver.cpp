// The contact solver on the CPU backend: strategies agree with each other and with
// Gauss-Seidel, impulses stay in their pyramid, divergence and bad settings are reported.
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/solvers/pgs.hpp"
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

TEST_CASE("Jacobi (every strategy), APGD, coloured Gauss-Seidel and the sequential reference converge to the same impulses", "[rbd_solver]") {
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
  {
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, Frictionless> c;
    prepare_solve(st.device(), c, s);
    SolverSettings<double> a = s;
    a.omega = 0;  // APGD's default
    const auto stats = JacobiSolver<device::cpu, double, Frictionless, Gather, Nesterov>().solve(st.device(), c, a);
    REQUIRE(stats.status == SolverStatus::converged);
    CHECK(stats.omega == Approx(0.3));
    CHECK(max_abs_diff(impulses(c), x_ref) < 1e-7 * largest);
    CHECK(max_abs_diff(velocities(st.device()), v_ref) < 1e-8);
  }

  Store cs(set);
  cs.syncDeviceFull();
  Contacts<device::cpu, double, Frictionless> cc;
  prepare_solve(cs.device(), cc, s);
  SolverSettings<double> cgs = s;
  cgs.omega = 0;  // its default, 1
  ColouredGaussSeidelSolver<device::cpu, double, Frictionless> solver;
  const auto stats = solver.solve(cs.device(), cc, cgs);
  REQUIRE(stats.status == SolverStatus::converged);
  CHECK(stats.omega == 1.0);
  CHECK(stats.colours >= 4);
  CHECK(max_abs_diff(impulses(cc), x_ref) < 1e-7 * largest);
  CHECK(max_abs_diff(velocities(cs.device()), v_ref) < 1e-8);
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
  World<device::cpu, double, PyramidFriction, Jacobi<UpdateCache>> w(set, s);
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
  s.max_retries = 0;  // adaptive under-relaxation off: see the next test case
  {
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, PyramidFriction> c;
    const auto r = jacobi<PyramidFriction, Gather>(st.device(), c, s);
    CHECK(r.status == SolverStatus::diverged);
    CHECK(r.retries == 0);
    CHECK(r.omega == 1.0);
    CHECK(r.total_iterations == r.iterations);
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
    t.max_retries = 2;  // restarting from a NaN velocity cannot help: every retry diverges as fast
    st.syncDeviceFull();  // the finite start again: detection refuses a NaN state (NonFiniteStateError)
    prepare_solve(st.device(), c, t);
    st.device().v(5, 2) = std::numeric_limits<double>::quiet_NaN();
    const auto rr = JacobiSolver<device::cpu, double, Frictionless, Atomic>().solve(st.device(), c, t);
    CHECK(rr.status == SolverStatus::diverged);
    CHECK(rr.retries == 2);
    CHECK(rr.omega == 0.5 * t.retry_omega_factor * t.retry_omega_factor);
    CHECK(rr.total_iterations == 3 * t.check_every);
  }
}

TEST_CASE("adaptive under-relaxation: a diverging solve restarts at a smaller omega", "[rbd_solver]") {
  auto set = pile<double>(3, 3);
  SolverSettings<double> s = tight();
  s.omega = 1.0;  // diverges on this pile (test case above)
  s.tolerance = 1e-6;
  s.max_iterations = 5000;
  REQUIRE(s.max_retries == 3);  // on by default
  REQUIRE(s.retry_omega_factor == 0.5);
  auto solve = [&](const SolverSettings<double>& t, auto model) {
    using Model = decltype(model);
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, Model> c;
    const auto r = jacobi<Model, Gather>(st.device(), c, t);
    return std::make_pair(r, velocities(st.device()));
  };
  const auto [r, v] = solve(s, PyramidFriction{});
  CHECK(r.status == SolverStatus::converged);
  REQUIRE(r.retries >= 1);
  CHECK(r.retries <= s.max_retries);
  CHECK(r.omega == s.omega * std::pow(s.retry_omega_factor, double(r.retries)));
  CHECK(r.total_iterations > r.iterations);  // the diverged attempts' iterations are counted
  CHECK(r.residual() < s.tolerance);
  CHECK(r.residuals.size() == r.checked_at.size());
  CHECK(r.checked_at.back() == r.iterations);  // the history is the last attempt's
  // The retry restarted from the solve's own start: it is exactly a plain solve at the final omega.
  SolverSettings<double> direct = s;
  direct.omega = r.omega;
  direct.max_retries = 0;
  const auto [d, vd] = solve(direct, PyramidFriction{});
  CHECK(d.status == SolverStatus::converged);
  CHECK(d.iterations == r.iterations);
  CHECK(max_abs_diff(v, vd) == 0.0);

  // Retries that all diverge: reported (and thrown when asked) with the last omega.
  SolverSettings<double> few = s;
  few.max_retries = 1;
  few.retry_omega_factor = 0.99;  // omega 0.99 diverges as well
  const auto [f, vf] = solve(few, PyramidFriction{});
  CHECK(f.status == SolverStatus::diverged);
  CHECK(f.retries == 1);
  CHECK(f.omega == Approx(0.99));
  few.throw_on_divergence = true;
  try {
    solve(few, PyramidFriction{});
    FAIL("no DivergenceError");
  } catch (const DivergenceError& e) {
    CHECK(e.retries() == 1);
    CHECK(e.omega() == Approx(0.99));
    CHECK(std::string(e.what()).find("after 1 retry") != std::string::npos);
  }

  // Gauss-Seidel shares the rule (it does not diverge on this pile even at omega 1.95:
  // a NaN velocity makes every attempt diverge).
  Store gs(set);
  gs.syncDeviceFull();
  Contacts<device::cpu, double, PyramidFriction> gc;
  prepare_solve(gs.device(), gc, s);
  gs.device().w(7, 0) = std::numeric_limits<double>::quiet_NaN();
  const auto g = solve_gauss_seidel(gs.device(), gc, s);
  CHECK(g.status == SolverStatus::diverged);
  CHECK(g.retries == s.max_retries);
  CHECK(g.omega == s.omega * std::pow(s.retry_omega_factor, double(s.max_retries)));
  CHECK(g.total_iterations == (s.max_retries + 1) * s.check_every);

  // Over-relaxed Gauss-Seidel whose residual grows (omega 1.95, any growth of
  // 5% counted) restarts at half the omega through the scaled blocks, and is
  // then exactly a plain solve at that omega.
  SolverSettings<double> over = s;
  over.omega = 1.95, over.divergence_growth = 1.05, over.tolerance = 2e-2, over.max_iterations = 2000;
  auto gauss_seidel = [&](const SolverSettings<double>& t) {
    Store st(set);
    st.syncDeviceFull();
    Contacts<device::cpu, double, ConeFriction> c;
    prepare_solve(st.device(), c, t);
    const auto r = ColouredGaussSeidelSolver<device::cpu, double, ConeFriction>().solve(st.device(), c, t);
    return std::make_pair(r, velocities(st.device()));
  };
  const auto [o, vo] = gauss_seidel(over);
  CHECK(o.status == SolverStatus::converged);
  REQUIRE(o.retries >= 1);
  CHECK(o.omega == over.omega * std::pow(over.retry_omega_factor, double(o.retries)));
  SolverSettings<double> plain = over;
  plain.omega = o.omega, plain.max_retries = 0;
  const auto [p, vp] = gauss_seidel(plain);
  CHECK(p.iterations == o.iterations);
  CHECK(max_abs_diff(vo, vp) == 0.0);
}

TEST_CASE("a retry's scaled inverse blocks are the blocks times the factor, exactly by a power of two",
          "[rbd_solver]") {
  // JacobiSolver retries at omega * factor by scaling dinv (InverseBlocks::scale):
  // the same bits as a smaller omega when the factor is a power of two.
  auto set = pile<double>(3, 3);
  Store st(set);
  st.syncDeviceFull();
  Contacts<device::cpu, double, ConeFriction> c;
  prepare_solve(st.device(), c, tight());
  REQUIRE(c.size() > 20);
  const auto b = st.device().view();
  const auto cv = c.view();
  auto blocks = [&](const double* scale) {
    launch(device::cpu{}, c.size(), InverseBlocks<ConeFriction, decltype(b), decltype(cv), double>{b, cv, scale});
    std::vector<double> d;
    for (std::size_t i = 0; i < c.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) d.push_back(c.dinv(i, k));
    return d;
  };
  const auto plain = blocks(nullptr);
  const double one = 1, quarter = 0.25, third = 1.0 / 3;
  CHECK(blocks(&one) == plain);
  const auto scaled = blocks(&quarter), other = blocks(&third);
  for (std::size_t k = 0; k < plain.size(); ++k) {
    CHECK(scaled[k] == plain[k] / 4);
    CHECK(std::fabs(other[k] - plain[k] / 3) <= 1e-15 * std::fabs(plain[k]));
  }
}

TEST_CASE("the residual check: largest contact residual, +inf for a non-finite velocity", "[rbd_solver]") {
  Bodies<device::cpu, double> b(6);
  VectorD1<double, device_is<device::cpu>> r(4);
  const double values[4] = {0.25, 3.5, 0.0, 1.0};
  for (std::size_t i = 0; i < 4; ++i) r(i) = values[i];
  ResidualCheck<device::cpu, double> check;
  CHECK(check(b.view(), r.view(), 4) == 3.5);
  CHECK(check(b.view(), r.view(), 1) == 0.25);  // only the first `contacts` entries count
  CHECK(check(b.view(), r.view(), 0) == 0.0);
  b.v(5, 1) = std::numeric_limits<double>::quiet_NaN();  // a body past the last contact
  CHECK(std::isinf(check(b.view(), r.view(), 4)));
  b.v(5, 1) = 0;
  b.w(2, 0) = -std::numeric_limits<double>::infinity();
  CHECK(std::isinf(check(b.view(), r.view(), 4)));
  b.w(2, 0) = 0;
  Bodies<device::cpu, double> few(2);  // more contacts than bodies
  r(3) = 7.0;
  CHECK(check(few.view(), r.view(), 4) == 7.0);
  CHECK(check.scratch_bytes() == 0);  // the host loop needs none
}

namespace {
template <class Method>
void check_bad_settings() {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  set.add_sphere({0, 0, 0.5}, 0.5, 1.0);
  auto with = [&](auto change) {
    SolverSettings<double> s;
    change(s);
    return error_of([&] { World<device::cpu, double, ConeFriction, Method> w(set, s); });
  };
  CHECK(with([](auto& s) { s.dt = 0; }).find("`dt`") != std::string::npos);
  CHECK(with([](auto& s) { s.dt = -1; }).find("`dt`") != std::string::npos);
  CHECK(with([](auto& s) { s.omega = -0.1; }).find("`omega`") != std::string::npos);
  CHECK(with([](auto& s) { s.omega = 2; }).find("`omega`") != std::string::npos);
  CHECK(with([](auto& s) { s.tolerance = 0; }).find("`tolerance`") != std::string::npos);
  CHECK(with([](auto& s) { s.friction = -0.1; }).find("`friction`") != std::string::npos);
  CHECK(with([](auto& s) { s.margin = -0.1; }).find("`margin`") != std::string::npos);
  CHECK(with([](auto& s) { s.correction = 0; }).find("`correction`") != std::string::npos);
  CHECK(with([](auto& s) { s.correction = 1.5; }).find("`correction`") != std::string::npos);
  CHECK(with([](auto& s) { s.substeps = 0; }).find("`substeps`") != std::string::npos);
  CHECK(with([](auto& s) { s.retry_omega_factor = 0; }).find("`retry_omega_factor`") != std::string::npos);
  CHECK(with([](auto& s) { s.retry_omega_factor = 1; }).find("`retry_omega_factor`") != std::string::npos);
  CHECK(with([](auto& s) { s.max_retries = 5000; }).find("`max_retries`") != std::string::npos);
  CHECK(with([](auto& s) { s.omega = 0; }).find("no InvalidArgumentError") != std::string::npos);  // the default
  CHECK(with([](auto& s) { s.check_every = 0; }).find("no InvalidArgumentError") != std::string::npos);  // the default
  CHECK(with([](auto& s) { s.max_retries = 0; }).find("no InvalidArgumentError") != std::string::npos);
  CHECK(with([](auto& s) { s.max_retries = 20; }).find("no InvalidArgumentError") != std::string::npos);
  CHECK(with([](auto&) {}).find("no InvalidArgumentError") != std::string::npos);
  World<device::cpu, double, ConeFriction, Method> w(set, SolverSettings<double>{});
  SolverSettings<double> bad;
  bad.omega = 2.5;
  CHECK_THROWS_AS(w.set_settings(bad), InvalidArgumentError);
  CHECK(w.settings().omega == SolverSettings<double>{}.omega);  // unchanged
}
}  // namespace

TEST_CASE("bad solver settings give InvalidArgumentError naming the field, for every method", "[rbd_solver]") {
  check_bad_settings<Jacobi<Gather>>();
  check_bad_settings<ColouredGaussSeidel>();
  check_bad_settings<AcceleratedJacobi<Gather>>();
  check_bad_settings<Substepping<>>();
  check_bad_settings<AcceleratedCG>();
}
