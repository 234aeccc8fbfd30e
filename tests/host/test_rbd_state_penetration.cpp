// Penetration from the bodies' states alone (statistics/state_penetration.hpp)
// against overlaps computed by hand: two boxes face on face, edge on face,
// corner on face; balls, capsules and planes; a compound's parts; a heap's
// contacts; the atlas's box scenes, which must start apart; only the pairs a
// filter counts; each overlapping pair once, to one visitor.
#include <array>
#include <cmath>
#include <map>

#include "catch_compat.hpp"
#include "gpusolve/rbd/statistics/state_penetration.hpp"
#include "gpusolve/rbd/world.hpp"
#include "test_rbd_scenes.hpp"
#include "../../bench/shared_pile.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;
using rbd_test::turn;

namespace {

// A fixed unit cube (half extent 0.5) at the origin and a moving one above it at
// height z, turned by q.
BodySet<double> cube_on_cube(double z, const std::array<double, 4>& q) {
  BodySet<double> set;
  set.add_fixed_box({0, 0, 0}, {0.5, 0.5, 0.5});
  set.add_box({0, 0, z}, {0.5, 0.5, 0.5}, 1.0, q);
  return set;
}

}  // namespace

TEST_CASE("state penetration of two boxes: face, edge and corner against a face", "[state_penetration]") {
  const double s2 = std::sqrt(2.0), s3 = std::sqrt(3.0);
  SECTION("face on face, 0.1 deep") {
    const StatePenetration p = state_penetration(cube_on_cube(0.9, {1, 0, 0, 0}));
    CHECK(p.relative == Approx(0.1 / 0.5));
    CHECK(p.a == 0);
    CHECK(p.b == 1);
  }
  SECTION("an edge 0.05 into a face") {  // turned 45 degrees about x: the lowest edge at z - 0.5 sqrt(2)
    CHECK(state_penetration(cube_on_cube(0.5 + 0.5 * s2 - 0.05, turn(M_PI / 4, 1, 0, 0))).relative ==
          Approx(0.05 / 0.5));
  }
  SECTION("a corner 0.04 into a face") {  // the diagonal (1, 1, 1) turned onto -z
    const double angle = std::acos(-1 / s3);
    const std::array<double, 4> q = turn(angle, -1 / s2, 1 / s2, 0);
    CHECK(state_penetration(cube_on_cube(0.5 + 0.5 * s3 - 0.04, q)).relative == Approx(0.04 / 0.5));
  }
  SECTION("apart, and touching") {
    CHECK(state_penetration(cube_on_cube(1.01, {1, 0, 0, 0})).relative == 0);
    CHECK(state_penetration(cube_on_cube(0.5 + 0.5 * s3 + 0.01, turn(std::acos(-1 / s3), -1 / s2, 1 / s2, 0)))
              .relative == 0);
  }
}

TEST_CASE("state penetration over the pairs a filter counts", "[state_penetration]") {
  // Two balls of radius 0.5 sinking 0.1 and 0.2 into the floor, and touching nothing else.
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  const std::size_t shallow = set.add_sphere({0, 0, 0.4}, 0.5, 1);
  const std::size_t deep = set.add_sphere({5, 0, 0.3}, 0.5, 1);
  CHECK(state_penetration(set).relative == Approx(0.2 / 0.5));
  CHECK(state_penetration(set).a == 0);
  CHECK(state_penetration(set).b == deep);
  const StatePenetration without_deep = state_penetration(set, [&](std::size_t i) { return i != deep; });
  CHECK(without_deep.relative == Approx(0.1 / 0.5));
  CHECK(without_deep.b == shallow);
  CHECK(state_penetration(set, [](std::size_t i) { return i != 0; }).relative == 0);  // the floor left out
}

TEST_CASE("every overlapping pair once, fixed pairs and separated ones not", "[state_penetration]") {
  // Two balls of radius 0.5 0.1 into each other above the floor, one of them
  // 0.05 into it, and two fixed boxes overlapping each other, which is no one's
  // penetration; a third ball alone.
  BodySet<double> set;
  const std::size_t floor = set.add_plane({0, 0, 1}, 0);
  const std::size_t a = set.add_sphere({0, 0, 0.45}, 0.5, 1), b = set.add_sphere({0.9, 0, 0.6}, 0.5, 1);
  set.add_fixed_box({10, 0, 1}, {1, 1, 1});
  set.add_fixed_box({11, 0, 1}, {1, 1, 1});
  set.add_sphere({-5, 0, 3}, 0.5, 1);
  std::map<std::pair<std::size_t, std::size_t>, double> seen;
  int calls = 0;
  for_each_state_overlap(set, [&](std::size_t i, std::size_t j, double relative) {
    ++calls;
    seen[{i, j}] = relative;
  });
  CHECK(calls == 2);
  REQUIRE(seen.size() == 2);
  CHECK(seen[{floor, a}] == Approx(0.05 / 0.5));
  CHECK(seen[{a, b}] == Approx((1.0 - std::hypot(0.9, 0.15)) / 0.5));
}

TEST_CASE("state penetration of balls, capsules, boxes and planes", "[state_penetration]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  SECTION("a ball 0.03 below the floor, relative to its radius") {
    set.add_sphere({0, 0, 0.47}, 0.5, 1.0);
    CHECK(state_penetration(set).relative == Approx(0.03 / 0.5));
  }
  SECTION("a box's lowest corner 0.02 below the floor, relative to its smallest half extent") {
    set.add_box({0, 0, 0.5 * std::sqrt(3.0) - 0.02}, {0.5, 0.5, 0.5}, 1.0,
                turn(std::acos(-1 / std::sqrt(3.0)), -1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0));
    CHECK(state_penetration(set).relative == Approx(0.02 / 0.5));
  }
  SECTION("two balls 0.1 into each other, the smaller radius 0.25") {
    set.add_sphere({0, 0, 5}, 0.5, 1.0);
    set.add_sphere({0.65, 0, 5}, 0.25, 1.0);
    CHECK(state_penetration(set).relative == Approx(0.1 / 0.25));
  }
  SECTION("a capsule lying across a box, 0.05 into its top face") {
    set.add_fixed_box({0, 0, 1}, {1, 1, 0.5});
    set.add_capsule({0.3, 0.2, 1.5 + 0.2 - 0.05}, 0.2, 0.6, 1.0);  // radius 0.2, along x
    CHECK(state_penetration(set).relative == Approx(0.05 / 0.2));
  }
  SECTION("a capsule's end 0.04 into a box's side, the deepest point at the segment's end") {
    set.add_fixed_box({0, 0, 5}, {0.5, 0.5, 0.5});
    set.add_capsule({0.5 + 0.6 + 0.2 - 0.04, 0, 5}, 0.2, 0.6, 1.0);
    CHECK(state_penetration(set).relative == Approx(0.04 / 0.2));
  }
  SECTION("a capsule across a box's edge near its end, 0.01 in: the deepest point inside the segment") {
    // The core crosses the edge along y at (0.5, 5.5) at right angles, 0.19
    // from it, 0.8 along from the centre: only a short stretch of it overlaps.
    set.add_fixed_box({0, 0, 5}, {0.5, 0.5, 0.5});
    const double r2 = std::sqrt(0.5);
    const std::array<double, 3> crossing{0.5 + 0.19 * r2, 0, 5.5 + 0.19 * r2}, u{r2, 0, -r2};
    set.add_capsule({crossing[0] - 0.8 * u[0], 0, crossing[2] - 0.8 * u[2]}, 0.2, 1.0, 1.0, turn(M_PI / 4, 0, 1, 0));
    CHECK(state_penetration(set).relative == Approx(0.01 / 0.2));
  }
  SECTION("two crossing capsules 0.06 into each other") {
    set.add_capsule({0, 0, 5}, 0.2, 1.0, 1.0);
    set.add_capsule({0, 0, 5.34}, 0.2, 1.0, 1.0, turn(M_PI / 2, 0, 0, 1));
    CHECK(state_penetration(set).relative == Approx(0.06 / 0.2));
  }
  SECTION("a compound's part counts; its own parts do not") {
    const std::vector<Part<double>> dumbbell = {{sphere, {0.3, 0, 0, 0}, {-0.5, 0, 0}, {1, 0, 0, 0}},
                                                {sphere, {0.3, 0, 0, 0}, {0.5, 0, 0}, {1, 0, 0, 0}},
                                                {capsule, {0.1, 0.5, 0, 0}, {0, 0, 0}, {1, 0, 0, 0}}};
    set.add_compound({0, 0, 0.29}, dumbbell, 1.0);  // both balls 0.01 into the floor
    CHECK(state_penetration(set).relative == Approx(0.01 / 0.1));  // the smallest part's feature: 0.1
  }
  SECTION("nothing touches") {
    set.add_sphere({0, 0, 2}, 0.5, 1.0);
    set.add_box({3, 0, 2}, {0.5, 0.5, 0.5}, 1.0);
    const StatePenetration p = state_penetration(set);
    CHECK(p.relative == 0);
    CHECK(p.a == p.b);
  }
}

TEST_CASE("a settled heap's penetration from the states agrees with the contacts' figure", "[state_penetration]") {
  // A 4 x 4 x 3 heap of every shape (test_rbd_scenes.hpp) after 1 s with 4
  // iterations a step, deep enough that the figures are not rounding; the
  // states of the last step's start, where its detection found its contacts.
  BodySet<float> set = rbd_test::mixed_heap<float>(4, 3);
  SolverSettings<float> s;
  s.max_iterations = 4;
  s.check_every = 4;
  World<device::cpu> world(set, s);
  world.advance(399);
  world.syncHost();
  const StatePenetration p = state_penetration(set);
  const double found = double(world.step().max_penetration);
  INFO("from the contacts " << found << ", from the states " << p.relative << " (bodies " << p.a << ", " << p.b << ")");
  CHECK(p.relative > 0);
  CHECK(std::fabs(p.relative - found) <= 0.1 * std::max(p.relative, found));
}

TEST_CASE("the atlas's scenes of boxes start with no body inside another", "[state_penetration]") {
  CHECK(state_penetration(gpusolve::bench::box_pyramid<double>(20)).relative == 0);
  CHECK(state_penetration(gpusolve::bench::pyramid_field<double>(20)).relative == 0);
  CHECK(state_penetration(gpusolve::bench::slab_tower<double>(100)).relative < 1e-12);  // layers touch: 0.2 is not exact in binary
  CHECK(state_penetration(gpusolve::bench::box_stack<double>(20)).relative == 0);
  CHECK(state_penetration(gpusolve::bench::cube_pile<double>(1000)).relative == 0);
  CHECK(gpusolve::bench::pyramid_field<double>(20).size() == 1 + 4200);
}
