// Materials on the CPU backend: restitution against the rebound height e^2 h,
// friction per material pair on one incline, and the errors bad materials get.
#include <array>
#include <cmath>
#include <string>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// A ball of radius 0.5 released with its lowest point h above the floor, of
// restitution e (a material of its own, or the world's default where
// `by_material` is false): the largest gap it reaches after its first impact.
template <class Method>
double rebound(double h, double e, bool by_material) {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  const std::size_t ball = set.add_sphere({0, 0, 0.5 + h}, 0.5, 1.0);
  SolverSettings<double> s;
  s.dt = 2.5e-4, s.margin = 0.02, s.tolerance = 1e-9, s.max_iterations = 200;
  if (by_material)
    set.set_material(ball, set.add_material({0.5, e}));  // the floor's default has e = 0: the larger wins
  else
    s.restitution = e;
  World<device::cpu, double, ConeFriction, Method> w(set, s);
  const double fall = std::sqrt(2 * h / g);  // the time to the first impact
  double top = 0, lowest = h;
  for (int k = 0; k * s.dt < 2.5 * fall; ++k) {  // past the first rebound's top, before the second impact
    w.step();
    w.syncHost();
    const double gap = set[ball].pos[2] - 0.5;
    if (k * s.dt < fall * 1.01) lowest = std::min(lowest, gap);
    else top = std::max(top, gap);
  }
  REQUIRE(lowest < 2e-3);  // it reached the floor
  return top;
}

template <class Method>
void check_rebound() {
  INFO(Method::name);
  for (double e : {0.5, 0.8}) {
    INFO("e = " << e);
    CHECK(rebound<Method>(1.0, e, true) == Approx(e * e).epsilon(0.01));
    CHECK(rebound<Method>(1.0, e, false) == Approx(e * e).epsilon(0.01));
  }
  CHECK(rebound<Method>(1.0, 0.0, true) < 1e-3);  // e = 0: it stays down
}

}  // namespace

TEST_CASE("a ball dropped from h rebounds to e^2 h with every method, and e = 0 does not bounce",
          "[rbd_physics][materials]") {
  for_every_method([](auto method) { check_rebound<decltype(method)>(); });
}

TEST_CASE("a slow impact below the restitution threshold does not bounce", "[rbd_physics][materials]") {
  // Dropped from 2 cm, the ball meets the floor at 0.63 m/s, below the 1 m/s threshold.
  CHECK(rebound<AcceleratedJacobi<Gather>>(0.02, 0.8, true) < 1e-4);
}

TEST_CASE("boxes of three materials on one incline: the pair's friction decides which slides",
          "[rbd_physics][materials]") {
  const double theta = 30 * M_PI / 180;  // tan = 0.577
  const std::array<double, 3> n = {-std::sin(theta), 0, std::cos(theta)};
  BodySet<double> set;
  const std::size_t ramp = set.add_plane(n, 0);
  const std::uint32_t rough = set.add_material({1.0, 0}), slick = set.add_material({0.09, 0}),
                      grippy = set.add_material({0.64, 0}), coated = set.add_material({0.09, 0});
  set.set_material(ramp, rough);
  set.set_material_pair(coated, rough, {0.8, 0});  // the pair overrides the combination
  const std::array<double, 4> q = turn(-theta, 0, 1, 0);
  std::array<std::size_t, 3> box{};
  const std::uint32_t materials[3] = {slick, grippy, coated};  // pair friction 0.3, 0.8, 0.8
  for (int k = 0; k < 3; ++k) {
    box[k] = set.add_box({0.5 * n[0], 3.0 * k, 0.5 * n[2]}, {0.5, 0.5, 0.5}, 1.0, q);
    set.set_material(box[k], materials[k]);
  }
  SolverSettings<double> s;
  s.dt = 0.002, s.margin = 0.02, s.tolerance = 1e-9, s.max_iterations = 400;
  World<device::cpu, double, ConeFriction, AcceleratedJacobi<Gather>> w(set, s);
  const double t = 0.6;
  for (int k = 0; k * s.dt < t - 1e-9; ++k) w.step();
  w.syncHost();
  auto moved = [&](std::size_t i) { return std::hypot(set[i].pos[0] - 0.5 * n[0], set[i].pos[2] - 0.5 * n[2]); };
  CHECK(moved(box[0]) == Approx(0.5 * g * (std::sin(theta) - 0.3 * std::cos(theta)) * t * t).epsilon(0.01));
  CHECK(moved(box[1]) < 1e-4);
  CHECK(moved(box[2]) < 1e-4);
}

TEST_CASE("bad materials are refused by name: friction, restitution, an unknown id, the default's pairs",
          "[rbd][materials]") {
  BodySet<float> set;
  const std::size_t ball = set.add_sphere({0, 0, 1}, 0.5f, 1.f);
  CHECK(refused_naming([&] { set.add_material({-0.1f, 0.f}); }, "material 1, field `friction`"));
  CHECK(refused_naming([&] { set.add_material({0.5f, 1.5f}); }, "field `restitution`"));
  try {
    set.set_material(ball, 3);
    FAIL("an unknown material id was taken");
  } catch (const InvalidBodyError& e) {
    CHECK(e.body() == ball);
    CHECK(e.field() == "material");
  }
  CHECK(set[ball].material == 0);  // the refused change left the body as it was
  const std::uint32_t m = set.add_material({0.3f, 0.2f});
  CHECK(m == 1);
  CHECK(refused_naming([&] { set.set_material_pair(0, m, {0.3f, 0.f}); }, "world's default"));
  set[ball].material = 5;  // changed in place: the set's validation names it
  try {
    set.validate();
    FAIL("validate() took an unknown material id");
  } catch (const InvalidBodyError& e) {
    CHECK(e.field() == "material");
  }
  SolverSettings<float> s;
  s.restitution = 1.5f;
  CHECK(refused_naming([&] { s.validate(); }, "restitution"));
}

TEST_CASE("a union's parts meet the floor with their own materials, or their body's", "[rbd][materials]") {
  BodySet<float> set;
  const std::size_t floor = set.add_plane({0, 0, 1}, 0);
  const std::uint32_t rough = set.add_material({1.f, 0.f}), slick = set.add_material({0.09f, 0.f}),
                      grippy = set.add_material({0.64f, 0.5f});
  set.set_material(floor, rough);
  std::vector<Part<float>> parts(2);
  for (int k = 0; k < 2; ++k) {
    parts[k].shape = box;
    parts[k].shape_param = {0.5f, 0.5f, 0.5f, 0.f};
    parts[k].pos = {k == 0 ? -0.5f : 0.5f, 0.f, 0.f};
  }
  parts[0].material = slick;  // part 1 names none: its body's
  const std::size_t sled = set.add_compound({0.f, 0.f, 0.49f}, parts, 2.f);
  set.set_material(sled, grippy);
  set[sled].v = {0.f, 0.f, -2.f};  // an impact above the threshold: the bounce follows the part too
  BodyManager<device::cpu> m(set);
  m.syncDevice();
  CollisionDetection<device::cpu> cd;
  Contacts<device::cpu, float, ConeFriction> c;
  const std::size_t n = cd.detect(m.device(), c, 0.05f, ContactDefaults<float>({0.5f, 0.f}, 1.f, 0.01f));
  REQUIRE(n == 4);  // the parts' 8 corners merged to the outer 4, two of each part
  std::size_t on_slick = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const bool slick_part = (c.feature(k) >> 24) == 0;  // the union's part, as the feature id carries it
    on_slick += slick_part;
    INFO("contact " << k << " at x = " << c.ra(k, 0));
    CHECK(c.ra(k, 0) * (slick_part ? 1 : -1) <= 1e-6f);  // part 0 lies at x <= 0
    CHECK(c.mu(k) == Approx(slick_part ? 0.3 : 0.8));                 // sqrt(0.09 * 1), sqrt(0.64 * 1)
    CHECK(c.bounce(k) == Approx(slick_part ? 0.0 : 0.5 * 2.0));        // max(0, 0), max(0.5, 0) times 2 m/s
  }
  CHECK(on_slick == 2);
  parts[1].material = 9;
  try {
    set.add_compound({5.f, 0.f, 1.f}, parts, 1.f);
    FAIL("a part's unknown material was taken");
  } catch (const InvalidBodyError& e) {
    CHECK(e.field() == "parts[1].material");
  }
  CHECK(set.parts().size() == 2);  // the refused union left no parts behind
}
