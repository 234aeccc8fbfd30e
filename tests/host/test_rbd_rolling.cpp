// Rolling and torsional resistance (ConeRollingFriction) on the CPU backend,
// against closed forms for a capsule rolling on its side and a sphere of
// radius R, mass m, I = 2/5 m R^2:
// rolling on a plane with resistance eta it decelerates at (5/7) g eta / R;
// on an incline it rests iff tan(theta) <= eta / R, else accelerates at
// (5/7) g (sin - eta/R cos); spinning about the normal with resistance mu_s
// it stops after 2 R^2 omega0 / (5 g mu_s). Every method that takes the
// model (AcceleratedCG is ConeFriction only).
#include <cmath>
#include <string>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

constexpr double R = 0.5;

SolverSettings<double> tight(double rolling, double spinning) {
  SolverSettings<double> s;
  s.dt = 1e-3, s.margin = 0.02, s.tolerance = 1e-10, s.max_iterations = 400;
  s.friction = 0.8, s.rolling = rolling, s.spinning = spinning;
  return s;
}

// A sphere resting on the plane through the origin with normal n (unit),
// moving along the plane's downhill direction at v0 and rolling without
// slipping; returns its speed along that direction after time t.
template <class Method>
double rolled_speed(double theta, double v0, double rolling, double t, double* travel = nullptr) {
  const double n[3] = {-std::sin(theta), 0, std::cos(theta)}, down[3] = {-std::cos(theta), 0, -std::sin(theta)};
  BodySet<double> set;
  set.add_plane({n[0], n[1], n[2]}, 0);
  const std::size_t ball = set.add_sphere({R * n[0], 0, R * n[2]}, R, 1.0);
  set[ball].v = {v0 * down[0], 0, v0 * down[2]};
  set[ball].w = {0, -v0 / R, 0};  // n x v / R: w x (-R n) = -v, the contact point at rest
  World<device::cpu, double, ConeRollingFriction, Method> w(set, tight(rolling, 0));
  for (int k = 0; k * 1e-3 < t - 1e-9; ++k) w.step();
  w.syncHost();
  if (travel != nullptr)
    *travel = (set[ball].pos[0] - R * n[0]) * down[0] + (set[ball].pos[2] - R * n[2]) * down[2];
  return set[ball].v[0] * down[0] + set[ball].v[2] * down[2];
}

}  // namespace

TEST_CASE("a rolling sphere decelerates at (5/7) g eta / R with every method", "[rbd_physics][rolling]") {
  for_every_method<ConeRollingFriction>([](auto method) {
    using Method = decltype(method);
    INFO(Method::name);
    const double eta = 0.01, v0 = 2, t = 1;
    const double a = (v0 - rolled_speed<Method>(0, v0, eta, t)) / t;
    CHECK(a == Approx(5.0 / 7.0 * g * eta / R).epsilon(0.01));
  });
}

TEST_CASE("a capsule rolling on its side decelerates at g eta / (R (1 + I / (m R^2))) with every method",
          "[rbd_physics][rolling]") {
  // Its axis along y, it rolls along x on the two points of its side; the
  // moment I about its axis is the library's (solid_capsule).
  for_every_method<ConeRollingFriction>([](auto method) {
    using Method = decltype(method);
    INFO(Method::name);
    const double eta = 0.01, v0 = 2, t = 1, r = 0.5;
    BodySet<double> set;
    set.add_plane({0, 0, 1}, 0);
    const std::size_t rod = set.add_capsule({0, 0, r}, r, 1.0, 1.0, turn(M_PI / 2, 0, 0, 1));
    set[rod].v = {v0, 0, 0};
    set[rod].w = {0, v0 / r, 0};  // n x v / R: the contact points at rest
    const double I = set[rod].inertia[0];  // about the body's x axis, its own
    World<device::cpu, double, ConeRollingFriction, Method> w(set, tight(eta, 0));
    for (int k = 0; k * 1e-3 < t - 1e-9; ++k) w.step();
    w.syncHost();
    CHECK((v0 - set[rod].v[0]) / t == Approx(g * eta / (r * (1 + I / (r * r)))).epsilon(0.01));
    CHECK(std::fabs(set[rod].pos[2] - r) < 1e-4);  // on the floor
  });
}

TEST_CASE("a sphere rests on an incline iff tan(theta) <= eta / R, else rolls down at (5/7) g (sin - eta/R cos)",
          "[rbd_physics][rolling]") {
  const double eta = 0.05;  // eta / R = 0.1: 5.71 degrees
  for_every_method<ConeRollingFriction>([&](auto method) {
    using Method = decltype(method);
    INFO(Method::name);
    double travel = 0;
    const double rest = rolled_speed<Method>(5.0 * M_PI / 180, 0, eta, 1, &travel);
    CHECK(std::fabs(rest) < 1e-4);
    CHECK(std::fabs(travel) < 1e-4);
    const double theta = 7.0 * M_PI / 180, t = 1;
    const double v = rolled_speed<Method>(theta, 0, eta, t);
    CHECK(v / t == Approx(5.0 / 7.0 * g * (std::sin(theta) - eta / R * std::cos(theta))).epsilon(0.01));
  });
}

TEST_CASE("a sphere spinning about the normal stops after 2 R^2 w0 / (5 g mu_s) with every method",
          "[rbd_physics][rolling]") {
  for_every_method<ConeRollingFriction>([](auto method) {
    using Method = decltype(method);
    INFO(Method::name);
    const double mu_s = 0.02, w0 = 2;
    BodySet<double> set;
    set.add_plane({0, 0, 1}, 0);
    const std::size_t ball = set.add_sphere({0, 0, R}, R, 1.0);
    set[ball].w = {0, 0, w0};
    World<device::cpu, double, ConeRollingFriction, Method> w(set, tight(0, mu_s));
    const double stop = 2 * R * R * w0 / (5 * g * mu_s);  // 1.02 s
    double stopped_at = -1;
    for (int k = 1; k * 1e-3 < 1.5 * stop; ++k) {
      w.step();
      w.syncHost();
      if (stopped_at < 0 && std::fabs(set[ball].w[2]) < 1e-6 * w0) stopped_at = k * 1e-3;
    }
    CHECK(stopped_at == Approx(stop).epsilon(0.01));
    CHECK(std::fabs(set[ball].w[2]) < 1e-6 * w0);  // and stays stopped
    CHECK(std::hypot(set[ball].pos[0], set[ball].pos[1]) < 1e-6);
  });
}

TEST_CASE("without resistance the rolling model steps a pile exactly as the cone does", "[rbd][rolling]") {
  // At zero rolling and spinning the angular rows stay zero, so each impulse,
  // velocity and position is the cone's to the bit; a fixed iteration count
  // (the angular rows add to the residual, and so to where a solve stops).
  auto run = [](auto model) {
    BodySet<float> set = pile<float>(4, 3);
    SolverSettings<float> s;
    s.dt = 0.005f, s.tolerance = 1e-30f, s.max_iterations = 40;
    World<device::cpu, float, decltype(model)> w(set, s);
    for (int k = 0; k < 50; ++k) w.step();
    w.syncHost();
    std::vector<float> state;
    for (std::size_t i = 0; i < set.size(); ++i)
      for (int c = 0; c < 3; ++c) state.insert(state.end(), {set[i].pos[c], set[i].v[c], set[i].w[c]});
    return state;
  };
  CHECK(run(ConeRollingFriction{}) == run(ConeFriction{}));
}

TEST_CASE("rolling or spinning resistance is refused by a World whose model has no angular rows",
          "[rbd][rolling]") {
  BodySet<float> set;
  set.add_plane({0, 0, 1}, 0);
  const std::size_t ball = set.add_sphere({0, 0, 0.5f}, 0.5f, 1.f);
  SolverSettings<float> s;
  s.rolling = 0.01f;
  CHECK(refused_naming([&] { World<device::cpu, float, ConeFriction> w(set, s); }, "`rolling`"));
  s.rolling = -1;
  CHECK(refused_naming([&] { s.validate(); }, "`rolling`"));
  CHECK(refused_naming([&] { set.add_material({0.5f, 0.f, 0.f, -0.1f}); }, "material 1, field `spinning`"));
  World<device::cpu, float, ConeFriction> w(set, SolverSettings<float>{});
  w.step();
  const std::size_t before = w.steps_queued();
  set.set_material(ball, set.add_material({0.5f, 0.f, 0.f, 0.01f}));
  w.manager().bodyAdded(ball);
  CHECK(refused_naming([&] { w.step(); }, "material 1, field `spinning`"));
  CHECK(w.steps_queued() == before);  // the refused step was not taken
  World<device::cpu, float, ConeRollingFriction> rolling(set, SolverSettings<float>{});
  rolling.step();  // the same materials are this model's to use
  CHECK(rolling.contacts().spin(0) == Approx(0.01f));
}
