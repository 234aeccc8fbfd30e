// Time integration: free fall against the closed form, forces and torques,
// a spinning non-isotropic body (gyroscopic term), the AABB update.
#include <cmath>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/integration/integrate.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;

TEST_CASE("free fall follows the semi-implicit Euler closed form", "[rbd][integrate]") {
  BodySet<double> s;
  s.add_sphere({1.0, 2.0, 100.0}, 0.5, 3.0);
  s[0].v = {0.5, 0.0, 4.0};
  s.add_plane({0.0, 0.0, 1.0}, 0.0);
  s.add_fixed_sphere({5.0, 5.0, 5.0}, 1.0);
  BodyManager<device::cpu, double> m(s);
  m.syncDevice();
  const double dt = 0.01, g = -9.81;
  const int steps = 200;
  for (int k = 0; k < steps; ++k) integrate(m.device(), dt, math::Vector3<double>(0.0, 0.0, g));
  m.syncHost();
  // v_n = v0 + n g dt, x_n = x0 + n dt v0 + g dt^2 n (n + 1) / 2 (velocity first, then position).
  const double n = steps, t = n * dt;
  CHECK(s[0].v[2] == Approx(4.0 + n * g * dt).epsilon(1e-12));
  CHECK(s[0].pos[2] == Approx(100.0 + n * dt * 4.0 + g * dt * dt * n * (n + 1) / 2).epsilon(1e-12));
  CHECK(s[0].pos[0] == Approx(1.0 + 0.5 * t).epsilon(1e-12));
  // ... which tends to the continuous solution: the error is g dt t / 2.
  CHECK(std::abs(s[0].pos[2] - (100.0 + 4.0 * t + g * t * t / 2)) == Approx(std::abs(g) * dt * t / 2).epsilon(1e-9));
  // Fixed bodies never move.
  CHECK(s[1].pos[2] == 0.0);
  CHECK(s[2].pos[2] == 5.0);
  CHECK(s[2].v[2] == 0.0);
}

TEST_CASE("forces and torques accelerate the body once and are consumed", "[rbd][integrate]") {
  BodySet<float> s;
  s.add_sphere({0.f, 0.f, 0.f}, 1.f, 2.f);  // I = 0.8
  s[0].force = {4.f, 0.f, 0.f};
  s[0].torque = {0.f, 0.f, 0.4f};
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  integrate(m.device(), 0.5f, math::Vector3<float>());
  integrate(m.device(), 0.5f, math::Vector3<float>());
  m.syncHost();
  CHECK(s[0].v[0] == Approx(0.5f * 4.f / 2.f));
  CHECK(s[0].w[2] == Approx(0.5f * 0.4f / 0.8f));
  CHECK(s[0].force[0] == 0.f);
  CHECK(s[0].torque[2] == 0.f);
  CHECK(s[0].pos[0] == Approx(2 * 0.5f * 1.f));  // two steps at v = 1
  // Turned by w dt twice about z.
  const float angle = 2 * 0.5f * 0.25f;
  CHECK(s[0].q[0] == Approx(std::cos(angle / 2)));
  CHECK(s[0].q[3] == Approx(std::sin(angle / 2)));
  CHECK(m.device().motion(0) > 0.f);
}

TEST_CASE("a spinning non-isotropic body keeps |q| = 1 and its angular momentum", "[rbd][integrate]") {
  BodySet<double> s;
  s.add_sphere({0.0, 0.0, 0.0}, 1.0, 1.0, {1.0, 2.0, 3.5});
  s[0].w = {0.2, 0.3, 3.0};  // mostly about the axis of largest inertia: a stable spin
  BodyManager<device::cpu, double> m(s);
  m.syncDevice();
  auto& d = m.device();
  // L = R I R^T w in the world frame.
  const auto momentum = [&d] {
    const BodyOffsets<double> off(d.view());
    const auto v = d.view();
    const math::Matrix3x3<double> R(math::Matrix3x3Global<double>(v.R, off.m9, 0));
    const math::Vector3<double> w(math::Vector3Global<double>(v.w, off.v3, 0));
    return math::Vector3<double>(math::rotate_tensor(R, math::Matrix3x3Global<double>(v.inertia, off.m9, 0)) * w);
  };
  const math::Vector3<double> L0 = momentum();
  const auto angular_velocity = [&d] { return math::Vector3<double>(d.w(0, 0), d.w(0, 1), d.w(0, 2)); };
  const math::Vector3<double> w0 = angular_velocity();
  for (int k = 0; k < 2000; ++k) {
    integrate(d, 1e-3, math::Vector3<double>());
    double qq = 0;
    for (int c = 0; c < 4; ++c) qq += d.q(0, c) * d.q(0, c);
    REQUIRE(std::sqrt(qq) == Approx(1.0).margin(1e-12));
  }
  const math::Vector3<double> L = momentum();
  const math::Vector3<double> w = angular_velocity();
  CHECK(math::norm(math::Vector3<double>(L - L0)) < 1e-10 * math::norm(L0));  // Move turns L with the body
  // The body precesses: w itself changed (were w kept instead of L, w would
  // stay put and L would wander).
  CHECK(math::norm(math::Vector3<double>(w - w0)) > 0.05);
}

TEST_CASE("integration moves the bounding-sphere AABB with the body", "[rbd][integrate]") {
  BodySet<float> s;
  s.add_sphere({0.f, 0.f, 0.f}, 0.25f, 1.f);
  s[0].v = {1.f, -2.f, 0.5f};
  s.add_fixed_box({3.f, 3.f, 3.f}, {0.3f, 0.4f, 1.2f});
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  auto& d = m.device();
  for (int k = 0; k < 10; ++k) integrate(d, 0.1f, math::Vector3<float>());
  for (int c = 0; c < 3; ++c) {
    CHECK(d.aabb(0, c) == Approx(d.pos(0, c) - 0.25f));
    CHECK(d.aabb(0, c + 3) == Approx(d.pos(0, c) + 0.25f));
    CHECK(d.aabb(1, c) == Approx(3.f - 1.3f));  // box: its bounding sphere, |h| = 1.3
  }
  CHECK(d.pos(0, 0) == Approx(1.f));
  CHECK(d.aabb(0, 1) == Approx(-2.25f));
}

TEST_CASE("integrate is apply_forces (velocities only) then move (positions only)", "[rbd][integrate]") {
  BodySet<double> s;
  s.add_sphere({0.0, 0.0, 1.0}, 1.0, 2.0, {1.0, 2.0, 3.5});  // non-isotropic: a gyroscopic term
  s[0].v = {0.5, -1.0, 2.0};
  s[0].w = {0.4, 1.5, 3.0};
  s[0].force = {1.0, 2.0, 3.0};
  s[0].torque = {0.3, -0.2, 0.1};
  s.add_fixed_sphere({5.0, 5.0, 5.0}, 1.0);
  BodyManager<device::cpu, double> whole(s), split(s);
  whole.syncDevice(), split.syncDevice();
  const double dt = 0.01;
  const math::Vector3<double> g(0.0, 0.0, -9.81);
  auto state = [](Bodies<device::cpu, double>& b, std::size_t k) {
    std::vector<double> out;
    for (int c = 0; c < 3; ++c) out.push_back(b.v(k, c)), out.push_back(b.w(k, c));
    for (int c = 0; c < 3; ++c) out.push_back(b.pos(k, c));
    for (int c = 0; c < 4; ++c) out.push_back(b.q(k, c));
    return out;
  };
  auto& d = split.device();
  const auto start = state(d, 0);
  apply_forces(d, dt, g);
  const auto forced = state(d, 0);
  for (int k = 0; k < 6; ++k) CHECK(forced[k] != start[k]);  // v and w changed ...
  for (int k = 6; k < 13; ++k) CHECK(forced[k] == start[k]);  // ... position and orientation did not
  CHECK(d.force(0, 2) == 0.0);
  CHECK(d.torque(0, 0) == 0.0);
  // In the principal frame (q = 1): dw = dt I^-1 tau; the gyroscopic part is move()'s.
  CHECK(forced[1] == Approx(0.4 + dt * 0.3 / 1.0));
  CHECK(forced[3] == Approx(1.5 + dt * -0.2 / 2.0));
  CHECK(forced[5] == Approx(3.0 + dt * 0.1 / 3.5));
  CHECK(forced[4] == Approx(2.0 + dt * (3.0 / 2.0 - 9.81)));
  move(d, dt);
  const auto moved = state(d, 0);
  for (int k = 0; k < 6; k += 2) CHECK(moved[k] == forced[k]);  // v stays; w turns with the body (Move)
  CHECK(moved[8] == start[8] + dt * forced[4]);  // z += dt v_z
  integrate(whole.device(), dt, g);
  CHECK(state(whole.device(), 0) == moved);  // same operations, same order: bitwise equal
  CHECK(state(d, 1) == state(whole.device(), 1));
  CHECK(d.pos(1, 0) == 5.0);  // fixed bodies do not move
}
