// Box-plane and box-box contact manifolds: hand-computed cases and random poses.
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/collision/pairs/box_box.hpp"
#include "gpusolve/rbd/collision/pairs/box_plane.hpp"

namespace {
namespace pairs_box_test {

using V = gpusolve::math::Vector3<float>;
using M = gpusolve::math::Matrix3x3<float>;
using Shape = gpusolve::rbd::PlacedShape<float>;
using Man = gpusolve::rbd::Manifold<float>;

const float r2 = std::sqrt(0.5f);  // sin 45 = cos 45

M rotation(const V& axis, float angle) {
  const V u = (1.f / gpusolve::math::norm(axis)) * axis;
  return gpusolve::math::to_rotation_matrix(gpusolve::math::Quaternion<float>::from_axis_angle(u, angle));
}

Shape box(const V& x, const M& R, float hx, float hy, float hz) { return {x, R, {hx, hy, hz, 0.f}}; }
Shape cube(const V& x, const M& R = M::identity()) { return box(x, R, 0.5f, 0.5f, 0.5f); }
Shape plane(const V& n, float d) { return {V(), M::identity(), {n[0], n[1], n[2], d}}; }

bool near(const V& a, const V& b, float eps = 1e-5f) {
  return std::fabs(a[0] - b[0]) <= eps && std::fabs(a[1] - b[1]) <= eps && std::fabs(a[2] - b[2]) <= eps;
}

void check_normal(const Man& m, float x, float y, float z) {
  CHECK(m.n[0] == Approx(x).margin(1e-5));
  CHECK(m.n[1] == Approx(y).margin(1e-5));
  CHECK(m.n[2] == Approx(z).margin(1e-5));
}

// Every expected point is in m (gap within 1e-5) and m holds nothing else.
void check_points(const Man& m, const std::vector<V>& expected, float gap) {
  REQUIRE(m.count == int(expected.size()));
  for (const V& e : expected) {
    int found = 0;
    for (int k = 0; k < m.count; ++k)
      if (near(m.points[k].p, e)) {
        ++found;
        CHECK(m.points[k].gap == Approx(gap).margin(1e-5));
      }
    INFO("expected point " << e[0] << " " << e[1] << " " << e[2]);
    CHECK(found == 1);
  }
}

std::set<std::uint32_t> features(const Man& m) {
  std::set<std::uint32_t> f;
  for (int k = 0; k < m.count; ++k) f.insert(m.points[k].feature);
  return f;
}

void check_distinct(const Man& m) { CHECK(int(features(m).size()) == m.count); }

// The same contact seen from the other box: same points and gaps, normal turned.
void check_swapped(const Man& ab, const Man& ba) {
  REQUIRE(ab.count == ba.count);
  CHECK(near(ab.n, V(-ba.n), 1e-5f));
  for (int k = 0; k < ab.count; ++k) {
    int found = 0;
    for (int l = 0; l < ba.count; ++l)
      if (near(ab.points[k].p, ba.points[l].p) && std::fabs(ab.points[k].gap - ba.points[l].gap) < 1e-5f) ++found;
    CHECK(found == 1);
  }
}

// Whether the world point w lies within box b grown by g.
bool inside(const Shape& b, const V& w, float g) {
  const V l = b.to_local(w);
  for (int k = 0; k < 3; ++k)
    if (std::fabs(l[k]) > b.p[k] + g) return false;
  return true;
}

V vertex(const Shape& b, int v) {
  V l;
  for (int k = 0; k < 3; ++k) l[k] = (v >> k) & 1 ? b.p[k] : -b.p[k];
  return b.to_world(l);
}

using gpusolve::rbd::box_box;
using gpusolve::rbd::box_plane;

TEST_CASE("box-plane: resting cube gives its 4 bottom corners", "[collision]") {
  const Shape ground = plane(V(0.f, 0.f, 1.f), 0.f);
  const Man m = box_plane(cube(V(0.2f, -0.3f, 0.49f)), ground, 0.05f);
  check_normal(m, 0.f, 0.f, 1.f);
  check_points(m, {V(-0.3f, -0.8f, -0.005f), V(0.7f, -0.8f, -0.005f), V(-0.3f, 0.2f, -0.005f), V(0.7f, 0.2f, -0.005f)},
               -0.01f);
  CHECK(features(m) == std::set<std::uint32_t>{0, 1, 2, 3});
  // A tilted plane: the cube turned with it gives the same contact in its frame.
  const V n(0.f, 0.6f, 0.8f);
  const M R = rotation(V(1.f, 0.f, 0.f), std::atan2(0.6f, 0.8f) * -1.f);  // takes z to n
  const Man t = box_plane(cube(V(2.f * n + 0.49f * n), R), plane(n, 2.f), 0.05f);
  check_normal(t, 0.f, 0.6f, 0.8f);
  REQUIRE(t.count == 4);
  for (int k = 0; k < 4; ++k) CHECK(t.points[k].gap == Approx(-0.01f).margin(1e-5));
}

TEST_CASE("box-plane: cube on an edge gives 2 points, on a corner 1", "[collision]") {
  const Shape ground = plane(V(0.f, 0.f, 1.f), 0.f);
  // 45 deg about x: the edge y = z = -0.5 (vertices 0, 1) points down, r2 below the centre.
  const Man e = box_plane(cube(V(0.f, 0.f, r2 - 0.01f), rotation(V(1.f, 0.f, 0.f), float(M_PI / 4))), ground, 0.05f);
  check_points(e, {V(-0.5f, 0.f, -0.005f), V(0.5f, 0.f, -0.005f)}, -0.01f);
  CHECK(features(e) == std::set<std::uint32_t>{0, 1});
  // Vertex 0 turned straight down: the diagonal (1, 1, 1) onto z, sqrt(3)/2 below the centre.
  const V diag(1.f, 1.f, 1.f);
  const M R = rotation(V(diag % V(0.f, 0.f, 1.f)), std::acos(1.f / std::sqrt(3.f)));
  const Man c = box_plane(cube(V(1.f, 2.f, std::sqrt(3.f) / 2 - 0.01f), R), ground, 0.05f);
  check_points(c, {V(1.f, 2.f, -0.005f)}, -0.01f);
  CHECK(c.points[0].feature == 0);
}

TEST_CASE("box-plane: margin filters points; a sunk box keeps its 4 deepest", "[collision]") {
  const Shape ground = plane(V(0.f, 0.f, 1.f), 0.f);
  CHECK(box_plane(cube(V(0.f, 0.f, 0.52f)), ground, 0.01f).count == 0);
  CHECK(box_plane(cube(V(0.f, 0.f, 0.52f)), ground, 0.f).count == 0);
  const Man m = box_plane(cube(V(0.f, 0.f, 0.52f)), ground, 0.03f);
  REQUIRE(m.count == 4);
  for (int k = 0; k < 4; ++k) CHECK(m.points[k].gap == Approx(0.02f));
  // Slightly tilted about x: the y = -0.5 corners are lower by sin(0.02); a margin between keeps only them.
  const float lift = std::sin(0.02f);
  const Man t = box_plane(cube(V(0.f, 0.f, 0.5f), rotation(V(1.f, 0.f, 0.f), 0.02f)), ground, 0.5f * lift);
  REQUIRE(t.count == 2);
  CHECK(features(t) == std::set<std::uint32_t>{0, 1});
  // All 8 vertices below the plane: the 4 bottom ones, 1.1 deep.
  const Man s = box_plane(cube(V(0.f, 0.f, -0.6f)), ground, 0.f);
  check_points(s, {V(-0.5f, -0.5f, -0.55f), V(0.5f, -0.5f, -0.55f), V(-0.5f, 0.5f, -0.55f), V(0.5f, 0.5f, -0.55f)},
               -1.1f);
  // On an edge with a margin reaching the 4 middle vertices: 6 qualify, 4 kept, the deepest among them.
  const Man r = box_plane(cube(V(0.f, 0.f, r2 - 0.01f), rotation(V(1.f, 0.f, 0.f), float(M_PI / 4))), ground, 0.8f);
  REQUIRE(r.count == 4);
  check_distinct(r);
  CHECK(features(r).count(0) == 1);
}

TEST_CASE("box-box: cube resting on a larger box, offset: 4 clipped corners", "[collision]") {
  const Shape big = box(V(), M::identity(), 2.f, 2.f, 0.5f);
  const Shape a = cube(V(0.3f, -0.2f, 0.99f));
  const Man m = box_box(a, big, 0.05f);
  check_normal(m, 0.f, 0.f, 1.f);
  check_points(m, {V(-0.2f, -0.7f, 0.495f), V(0.8f, -0.7f, 0.495f), V(-0.2f, 0.3f, 0.495f), V(0.8f, 0.3f, 0.495f)},
               -0.01f);
  check_distinct(m);
  check_swapped(m, box_box(big, a, 0.05f));
  // A hair higher and sideways: the same features.
  const Man moved = box_box(cube(V(0.3001f, -0.1999f, 0.9901f)), big, 0.05f);
  CHECK(features(moved) == features(m));
  // Separated by 0.1: nothing within a 0.05 margin, the 4 corners within 0.2.
  CHECK(box_box(cube(V(0.3f, -0.2f, 1.1f)), big, 0.05f).count == 0);
  const Man far = box_box(cube(V(0.3f, -0.2f, 1.1f)), big, 0.2f);
  check_points(far, {V(-0.2f, -0.7f, 0.55f), V(0.8f, -0.7f, 0.55f), V(-0.2f, 0.3f, 0.55f), V(0.8f, 0.3f, 0.55f)}, 0.1f);
}

TEST_CASE("box-box: cube turned 45 deg about z on a big box: its 4 bottom corners", "[collision]") {
  const Shape big = box(V(), M::identity(), 2.f, 2.f, 0.5f);
  const Shape a = cube(V(0.5f, 0.25f, 0.98f), rotation(V(0.f, 0.f, 1.f), float(M_PI / 4)));
  const Man m = box_box(a, big, 0.05f);
  check_normal(m, 0.f, 0.f, 1.f);
  check_points(m,
               {V(0.5f + r2, 0.25f, 0.49f), V(0.5f - r2, 0.25f, 0.49f), V(0.5f, 0.25f + r2, 0.49f),
                V(0.5f, 0.25f - r2, 0.49f)},
               -0.02f);
  check_distinct(m);
  check_swapped(m, box_box(big, a, 0.05f));
  const Man moved = box_box(cube(V(0.5001f, 0.2501f, 0.98f), a.R), big, 0.05f);
  CHECK(features(moved) == features(m));
}

TEST_CASE("box-box: cube over the big box's edge: the clipped polygon reduced to 4", "[collision]") {
  const Shape big = box(V(), M::identity(), 2.f, 2.f, 0.5f);
  const Shape a = cube(V(1.8f, 0.3f, 0.99f), rotation(V(0.f, 0.f, 1.f), float(M_PI / 6)));
  const Man m = box_box(a, big, 0.05f);
  check_normal(m, 0.f, 0.f, 1.f);
  // The footprint's corners with x < 2 and the two crossings of its sides with x = 2.
  std::vector<V> polygon;
  for (int v = 0; v < 4; ++v) {  // the bottom corners; their edges join v and v ^ 1, v and v ^ 2
    const V p = vertex(a, v);
    if (p[0] < 2.f) polygon.push_back(V(p[0], p[1], 0.495f));
    for (int w : {v | 1, v | 2}) {
      const V r = vertex(a, w);
      if (w != v && (p[0] - 2.f) * (r[0] - 2.f) < 0.f) {
        const float t = (2.f - p[0]) / (r[0] - p[0]);
        polygon.push_back(V(2.f, p[1] + t * (r[1] - p[1]), 0.495f));
      }
    }
  }
  REQUIRE(polygon.size() == 5);
  REQUIRE(m.count == 4);
  check_distinct(m);
  for (int k = 0; k < m.count; ++k) {
    CHECK(m.points[k].gap == Approx(-0.01f).margin(1e-5));
    int found = 0;
    for (const V& e : polygon) found += near(m.points[k].p, e);
    CHECK(found == 1);
    CHECK(inside(big, m.points[k].p, 0.006f));
    CHECK(inside(a, m.points[k].p, 0.006f));
  }
  const Man moved = box_box(cube(V(1.8001f, 0.2999f, 0.99f), a.R), big, 0.05f);
  CHECK(features(moved) == features(m));
}

TEST_CASE("box-box: a resting pair keeps its feature ids as rounding and small tilts change from step to step",
          "[collision]") {
  // The warm start finds a point by its feature id: where the ids change
  // while the points stay, the pair starts cold.
  const float tilts[][2] = {{0, 0}, {1e-6f, 0}, {-1e-6f, 0}, {0, 1e-6f}, {0, -1e-6f}, {2e-5f, 1e-5f}, {-1e-5f, 2e-5f}};
  const auto tilted = [](const V& x, float about_x, float about_y, const M& R = M::identity()) {
    return cube(x, M(rotation(V(1.f, 0.f, 0.f), about_x) * rotation(V(0.f, 1.f, 0.f), about_y) * R));
  };
  SECTION("a cube on a cube of its width, moved along x: its sides along y lie in the other's") {
    const Shape below = cube(V(0.f, 0.f, 0.5f));
    const Man m = box_box(below, cube(V(0.02f, 0.f, 1.4999f)), 0.05f);
    REQUIRE(m.count == 4);
    for (const auto& t : tilts)
      for (float dy : {0.f, 1e-7f, -1e-7f, 3e-7f}) {
        INFO("tilt " << t[0] << " " << t[1] << ", moved " << dy << " along y");
        CHECK(features(box_box(below, tilted(V(0.02f, dy, 1.4999f), t[0], t[1]), 0.05f)) == features(m));
      }
  }
  SECTION("a cube turned 30 degrees on a cube: an octagon reduced to four") {
    const Shape below = cube(V(0.f, 0.f, 0.5f));
    const M turned = rotation(V(0.f, 0.f, 1.f), float(M_PI / 6));
    const Man m = box_box(below, tilted(V(0.f, 0.f, 1.4999f), 0, 0, turned), 0.05f);
    REQUIRE(m.count == 4);
    for (const auto& t : tilts) {
      INFO("tilt " << t[0] << " " << t[1]);
      CHECK(features(box_box(below, tilted(V(0.f, 0.f, 1.4999f), t[0], t[1], turned), 0.05f)) == features(m));
    }
  }
}

TEST_CASE("box-box: crossed edges give one point between them", "[collision]") {
  // b's top edge runs along x at y = 0, z = r2; a's bottom edge along y at x = 0.1, z = 1.4042 - r2.
  const Shape b = cube(V(), rotation(V(1.f, 0.f, 0.f), float(M_PI / 4)));
  const Shape a = cube(V(0.1f, -0.15f, 2 * r2 - 0.01f), rotation(V(0.f, 1.f, 0.f), float(M_PI / 4)));
  const Man m = box_box(a, b, 0.05f);
  check_normal(m, 0.f, 0.f, 1.f);  // along a's y x b's x, from b to a
  check_points(m, {V(0.1f, 0.f, r2 - 0.005f)}, -0.01f);
  check_swapped(m, box_box(b, a, 0.05f));
  const Man moved = box_box(cube(V(0.1001f, -0.1499f, 2 * r2 - 0.0099f), a.R), b, 0.05f);
  CHECK(features(moved) == features(m));
  CHECK((m.points[0].feature >> 13) == 1u);
  // Lifted 0.1 clear: none within 0.05, the point within 0.2.
  const Shape up = cube(V(0.1f, -0.15f, 2 * r2 + 0.1f), a.R);
  CHECK(box_box(up, b, 0.05f).count == 0);
  check_points(box_box(up, b, 0.2f), {V(0.1f, 0.f, r2 + 0.05f)}, 0.1f);
}

TEST_CASE("box-box: a cube nearly flat over another's edge gives its face's points, not one edge point",
          "[collision]") {
  // b turned 0.6 rad about z and tilted 0.01 to 0.04 rad about x, its centre
  // beyond a's edge at x = 0.5, its bottom 0.005 to 0.02 above a's top. An edge
  // of each lies almost flat, their crossing axis almost vertical: before, that
  // axis won and gave one point, leaving the rest of b's face free to sink into
  // a within a step; the face's clipped points hold it.
  const Shape a = cube(V());
  for (float tilt : {0.01f, 0.02f, 0.04f})
    for (float gap : {0.005f, 0.02f}) {
      const M R = rotation(V(1.f, 0.f, 0.f), tilt) * rotation(V(0.f, 0.f, 1.f), 0.6f);
      const Shape b = cube(V(0.8f, 0.1f, 1.f + gap + 0.6f * tilt), R);
      const Man m = box_box(b, a, 0.1f);
      INFO("tilt " << tilt << ", gap " << gap);
      REQUIRE(m.count == 4);
      CHECK(std::fabs(m.n[2]) > std::cos(tilt) - 1e-5f);  // b's face normal: a face contact
      for (int k = 0; k < m.count; ++k) {
        CHECK(m.points[k].p[0] < 0.5f + 1e-4f);  // over a
        CHECK(m.points[k].gap > 0.f);
        CHECK(m.points[k].gap < 0.1f);
      }
      check_swapped(m, box_box(a, b, 0.1f));
    }
}

TEST_CASE("box-box and box-plane on random poses: unit normal, points within both boxes, none when apart",
          "[collision]") {
  std::mt19937 rng(20240611u);
  std::uniform_real_distribution<float> pos(-1.5f, 1.5f), half(0.2f, 1.f), unit(-1.f, 1.f), ang(0.f, 6.2831853f);
  const auto random_box = [&] {
    const V axis(unit(rng), unit(rng), unit(rng) + 2.f);  // never zero
    return box(V(pos(rng), pos(rng), pos(rng)), rotation(axis, ang(rng)), half(rng), half(rng), half(rng));
  };
  const float margin = 0.05f;
  int contacts = 0, overlapping = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Shape a = random_box(), b = random_box();
    const Man m = box_box(a, b, margin);
    INFO("trial " << trial);
    CHECK(m.count <= 4);
    check_distinct(m);
    if (m.count > 0) {
      ++contacts;
      CHECK(gpusolve::math::norm(m.n) == Approx(1.f).margin(1e-5));
    }
    // No point is deeper than the boxes overlap along the normal.
    const float sep = std::fabs(gpusolve::math::dot(V(a.x - b.x), m.n)) - gpusolve::rbd::detail::box_radius(a, m.n) -
                      gpusolve::rbd::detail::box_radius(b, m.n);
    for (int k = 0; k < m.count; ++k) {
      CHECK(m.points[k].gap >= sep - 1e-4f);
      const float g = std::fabs(m.points[k].gap) + 1e-4f;
      CHECK(m.points[k].gap < margin);
      CHECK(inside(a, m.points[k].p, g));
      CHECK(inside(b, m.points[k].p, g));
    }
    const float ra = gpusolve::math::norm(V(a.p[0], a.p[1], a.p[2])), rb = gpusolve::math::norm(V(b.p[0], b.p[1], b.p[2]));
    if (gpusolve::math::norm(V(a.x - b.x)) - ra - rb > margin) CHECK(m.count == 0);
    // A vertex of one box well inside the other: they overlap, so a point with negative gap.
    bool deep = false;
    for (int v = 0; v < 8; ++v) deep = deep || inside(b, vertex(a, v), -1e-3f) || inside(a, vertex(b, v), -1e-3f);
    if (deep) {
      ++overlapping;
      REQUIRE(m.count > 0);
      float lowest = 1.f;
      for (int k = 0; k < m.count; ++k) lowest = std::fmin(lowest, m.points[k].gap);
      CHECK(lowest < 0.f);
    }
    // The plane through b's centre, normal a random direction: the deepest vertex is always kept.
    V n(unit(rng), unit(rng), unit(rng) + 2.f);
    n = V((1.f / gpusolve::math::norm(n)) * n);
    const Man p = box_plane(a, plane(n, gpusolve::math::dot(n, b.x)), margin);
    float lowest = 1e9f;
    for (int v = 0; v < 8; ++v) lowest = std::fmin(lowest, gpusolve::math::dot(n, vertex(a, v)) - gpusolve::math::dot(n, b.x));
    CHECK(p.count <= 4);
    check_distinct(p);
    if (lowest < margin) {
      REQUIRE(p.count > 0);
      CHECK(near(p.n, n));
      float got = 1e9f;
      for (int k = 0; k < p.count; ++k) got = std::fmin(got, p.points[k].gap);
      CHECK(got == Approx(lowest).margin(1e-5));
    } else {
      CHECK(p.count == 0);
    }
  }
  CHECK(contacts > 400);  // the poses really meet, often
  CHECK(overlapping > 200);
}

TEST_CASE("box-plane and box-box in double precision", "[collision]") {
  using VD = gpusolve::math::Vector3<double>;
  using MD = gpusolve::math::Matrix3x3<double>;
  const gpusolve::rbd::PlacedShape<double> c{VD(0.0, 0.0, 0.49), MD::identity(), {0.5, 0.5, 0.5, 0.0}};
  const gpusolve::rbd::PlacedShape<double> ground{VD(), MD::identity(), {0.0, 0.0, 1.0, 0.0}};
  const gpusolve::rbd::PlacedShape<double> slab{VD(0.0, 0.0, -1.0), MD::identity(), {3.0, 3.0, 1.0, 0.0}};
  const auto p = box_plane(c, ground, 0.05);
  const auto b = box_box(c, slab, 0.05);
  REQUIRE(p.count == 4);
  REQUIRE(b.count == 4);
  for (int k = 0; k < 4; ++k) {
    CHECK(p.points[k].gap == Approx(-0.01).margin(1e-12));
    CHECK(b.points[k].gap == Approx(-0.01).margin(1e-12));
    CHECK(b.points[k].p[2] == Approx(-0.005).margin(1e-12));
  }
  CHECK(b.n[2] == 1.0);
}

}  // namespace pairs_box_test
}  // namespace
