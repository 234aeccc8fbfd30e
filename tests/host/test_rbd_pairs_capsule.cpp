// Capsule contact manifolds (sphere, plane, capsule, box): hand-computed cases,
// symmetry, feature ids, and random poses against brute-force distances.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_box.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_capsule.hpp"
#include "gpusolve/rbd/collision/pairs/capsule_plane.hpp"
#include "gpusolve/rbd/collision/pairs/segment.hpp"
#include "gpusolve/rbd/collision/pairs/sphere_capsule.hpp"

namespace {
namespace pairs_capsule_test {

using namespace gpusolve::rbd;
using V = gpusolve::math::Vector3<float>;
using M = gpusolve::math::Matrix3x3<float>;
using Shape = PlacedShape<float>;
using Man = Manifold<float>;
using gpusolve::math::dot;
using gpusolve::math::norm;

const float pi = 3.14159265358979f;

// Rotation by angle about axis (Rodrigues).
M rotation(const V& axis, float angle) {
  const V k = (1.f / norm(axis)) * axis;
  const float c = std::cos(angle), s = std::sin(angle), t = 1.f - c;
  return M(c + t * k[0] * k[0], t * k[0] * k[1] - s * k[2], t * k[0] * k[2] + s * k[1],  //
           t * k[1] * k[0] + s * k[2], c + t * k[1] * k[1], t * k[1] * k[2] - s * k[0],  //
           t * k[2] * k[0] - s * k[1], t * k[2] * k[1] + s * k[0], c + t * k[2] * k[2]);
}

// A rotation whose column 0 (the capsule's axis) is dir.
M frame_along(const V& dir) {
  const V u = (1.f / norm(dir)) * dir;
  const V v = unit_perpendicular(u);
  const V w = u % v;
  return M(u[0], v[0], w[0], u[1], v[1], w[1], u[2], v[2], w[2]);
}

Shape capsule(const V& x, const V& dir, float r, float L) { return {x, frame_along(dir), {r, L, 0.f, 0.f}}; }
Shape sphere(const V& x, float r) { return {x, M::identity(), {r, 0.f, 0.f, 0.f}}; }
Shape plane(const V& n, float d) { return {V(), M::identity(), {n[0], n[1], n[2], d}}; }
Shape box(const V& x, const M& R, float hx, float hy, float hz) { return {x, R, {hx, hy, hz, 0.f}}; }

bool near(const V& a, const V& b, float eps = 1e-5f) {
  return std::fabs(a[0] - b[0]) <= eps && std::fabs(a[1] - b[1]) <= eps && std::fabs(a[2] - b[2]) <= eps;
}

void check_vec(const V& v, const V& want, float eps = 1e-5f) {
  INFO("got (" << v[0] << ", " << v[1] << ", " << v[2] << "), want (" << want[0] << ", " << want[1] << ", "
               << want[2] << ")");
  CHECK(near(v, want, eps));
}

// Point k of m at p with gap g and feature f.
void check_point(const Man& m, int k, const V& p, float g, std::uint32_t f, float eps = 1e-5f) {
  REQUIRE(k < m.count);
  check_vec(m.points[k].p, p, eps);
  CHECK(m.points[k].gap == Approx(g).margin(eps));
  CHECK(m.points[k].feature == f);
}

bool finite_unit(const V& n) {
  return std::isfinite(n[0]) && std::isfinite(n[1]) && std::isfinite(n[2]) && std::fabs(norm(n) - 1.f) < 1e-4f;
}

bool distinct_features(const Man& m) {
  for (int i = 0; i < m.count; ++i)
    for (int j = i + 1; j < m.count; ++j)
      if (m.points[i].feature == m.points[j].feature) return false;
  return true;
}

std::vector<std::uint32_t> features(const Man& m) {
  std::vector<std::uint32_t> f;
  for (int k = 0; k < m.count; ++k) f.push_back(m.points[k].feature);
  return f;
}

Shape moved(Shape s, const V& by) {
  s.x = V(s.x + by);
  return s;
}

float min_gap(const Man& m) {
  float g = 1e30f;
  for (int k = 0; k < m.count; ++k) g = std::fmin(g, m.points[k].gap);
  return g;
}

// --- brute force, in double, independent of the library's segment code ---
struct D3 {
  double v[3];
};
D3 d3(const V& a) { return {{a[0], a[1], a[2]}}; }
D3 lerp(const D3& a, const D3& b, double t) {
  return {{a.v[0] + t * (b.v[0] - a.v[0]), a.v[1] + t * (b.v[1] - a.v[1]), a.v[2] + t * (b.v[2] - a.v[2])}};
}
double dist(const D3& a, const D3& b) {
  const double x = a.v[0] - b.v[0], y = a.v[1] - b.v[1], z = a.v[2] - b.v[2];
  return std::sqrt(x * x + y * y + z * z);
}

// min over 2001 x 2001 samples of the two cores' distance
double brute_segments(const D3& a0, const D3& a1, const D3& b0, const D3& b1) {
  const int n = 2000;
  double best = 1e30;
  for (int i = 0; i <= n; ++i) {
    const D3 p = lerp(a0, a1, double(i) / n);
    for (int j = 0; j <= n; ++j) best = std::fmin(best, dist(p, lerp(b0, b1, double(j) / n)));
  }
  return best;
}

// min over 20001 samples of the core's distance to the box (in the box frame)
double brute_segment_box(const D3& p0, const D3& p1, const double h[3]) {
  const int n = 20000;
  double best = 1e30;
  for (int i = 0; i <= n; ++i) {
    const D3 p = lerp(p0, p1, double(i) / n);
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double o = std::fmax(std::fabs(p.v[k]) - h[k], 0.0);
      s += o * o;
    }
    best = std::fmin(best, std::sqrt(s));
  }
  return best;
}

// ---------------------------------------------------------------- segments

TEST_CASE("segment helpers: point-segment and segment-segment closest points", "[collision]") {
  CHECK(segment_closest_param(V(0.f, 0.f, 0.f), V(2.f, 0.f, 0.f), V(0.5f, 3.f, 0.f)) == Approx(0.25f));
  CHECK(segment_closest_param(V(0.f, 0.f, 0.f), V(2.f, 0.f, 0.f), V(-1.f, 3.f, 0.f)) == 0.f);
  CHECK(segment_closest_param(V(0.f, 0.f, 0.f), V(0.f, 0.f, 0.f), V(-1.f, 3.f, 0.f)) == 0.f);
  // crossed at right angles, 1 apart
  const auto x = segment_segment_closest(V(-1.f, 0.f, 1.f), V(1.f, 0.f, 1.f), V(0.5f, -1.f, 0.f), V(0.5f, 1.f, 0.f));
  CHECK(x.s == Approx(0.75f));
  CHECK(x.t == Approx(0.5f));
  CHECK(x.dist2 == Approx(1.f));
  // parallel, no overlap: end to end
  const auto p = segment_segment_closest(V(0.f, 0.f, 0.f), V(1.f, 0.f, 0.f), V(3.f, 1.f, 0.f), V(2.f, 1.f, 0.f));
  CHECK(p.dist2 == Approx(2.f));
  check_vec(p.c1, V(1.f, 0.f, 0.f));
  check_vec(p.c2, V(2.f, 1.f, 0.f));
  // parallel, overlapping: the distance is exact, the points within the overlap
  const auto o = segment_segment_closest(V(0.f, 0.f, 0.f), V(2.f, 0.f, 0.f), V(1.f, 0.5f, 0.f), V(3.f, 0.5f, 0.f));
  CHECK(o.dist2 == Approx(0.25f));
  CHECK(o.c1[0] >= 1.f - 1e-6f);
  // degenerate: both points
  const auto d = segment_segment_closest(V(1.f, 0.f, 0.f), V(1.f, 0.f, 0.f), V(0.f, 0.f, 0.f), V(0.f, 0.f, 0.f));
  CHECK(d.dist2 == Approx(1.f));
  CHECK(unit_perpendicular(V(0.f, 0.f, 1.f))[2] == 0.f);
  CHECK(finite_unit(unit_perpendicular(V(0.6f, 0.8f, 0.f))));
}

// ---------------------------------------------------------------- sphere-capsule

TEST_CASE("sphere-capsule: side, end cap, overlap, tilted, centre on the core, margin", "[collision]") {
  const Shape cap = capsule(V(0.f, 0.f, 0.f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
  {  // above the side: closest core point (0.5, 0, 0)
    const Man m = sphere_capsule(sphere(V(0.5f, 0.f, 1.f), 0.25f), cap, 0.3f);
    REQUIRE(m.count == 1);
    check_vec(m.n, V(0.f, 0.f, 1.f));
    check_point(m, 0, V(0.5f, 0.f, 0.625f), 0.25f, 0u);
    CHECK(sphere_capsule(sphere(V(0.5f, 0.f, 1.f), 0.25f), cap, 0.25f).count == 0);  // gap not below margin
    CHECK(sphere_capsule(sphere(V(0.5f, 0.f, 3.f), 0.25f), cap, 0.3f).count == 0);
  }
  {  // beyond the +x end cap
    const Man m = sphere_capsule(sphere(V(2.f, 0.f, 0.f), 0.25f), cap, 0.3f);
    REQUIRE(m.count == 1);
    check_vec(m.n, V(1.f, 0.f, 0.f));
    check_point(m, 0, V(1.625f, 0.f, 0.f), 0.25f, 0u);
  }
  {  // overlapping the side
    const Man m = sphere_capsule(sphere(V(0.f, 0.6f, 0.f), 0.25f), cap, 0.f);
    REQUIRE(m.count == 1);
    check_vec(m.n, V(0.f, 1.f, 0.f));
    check_point(m, 0, V(0.f, 0.425f, 0.f), -0.15f, 0u);
  }
  {  // tilted capsule, translated
    const V u(0.6f, 0.8f, 0.f), x0(1.f, 2.f, 3.f);
    const Man m = sphere_capsule(sphere(V(x0 + 0.5f * u + V(0.f, 0.f, 1.f)), 0.25f), capsule(x0, u, 0.5f, 1.f), 0.3f);
    REQUIRE(m.count == 1);
    check_vec(m.n, V(0.f, 0.f, 1.f));
    check_point(m, 0, V(x0 + 0.5f * u + V(0.f, 0.f, 0.625f)), 0.25f, 0u);
  }
  {  // centre on the core: a unit normal across the axis
    const Man m = sphere_capsule(sphere(V(0.3f, 0.f, 0.f), 0.25f), cap, 0.f);
    REQUIRE(m.count == 1);
    CHECK(finite_unit(m.n));
    CHECK(std::fabs(m.n[0]) < 1e-6f);
    CHECK(m.points[0].gap == Approx(-0.75f));
  }
}

// ---------------------------------------------------------------- capsule-plane

TEST_CASE("capsule-plane: lying flat 2 points, standing 1, tilted, sunk, margin", "[collision]") {
  const Shape ground = plane(V(0.f, 0.f, 1.f), 0.f);
  {  // lying flat, touching
    const Man m = capsule_plane(capsule(V(0.f, 0.f, 0.5f), V(1.f, 0.f, 0.f), 0.5f, 1.f), ground, 0.01f);
    REQUIRE(m.count == 2);
    check_vec(m.n, V(0.f, 0.f, 1.f));
    check_point(m, 0, V(-1.f, 0.f, 0.f), 0.f, 0u);
    check_point(m, 1, V(1.f, 0.f, 0.f), 0.f, 1u);
  }
  {  // lying flat, sunk by 0.1
    const Man m = capsule_plane(capsule(V(0.f, 0.f, 0.4f), V(1.f, 0.f, 0.f), 0.5f, 1.f), ground, 0.f);
    REQUIRE(m.count == 2);
    check_point(m, 0, V(-1.f, 0.f, -0.05f), -0.1f, 0u);
    check_point(m, 1, V(1.f, 0.f, -0.05f), -0.1f, 1u);
  }
  {  // standing on its -x end
    const Man m = capsule_plane(capsule(V(0.f, 0.f, 1.5f), V(0.f, 0.f, 1.f), 0.5f, 1.f), ground, 0.1f);
    REQUIRE(m.count == 1);
    check_point(m, 0, V(0.f, 0.f, 0.f), 0.f, 0u);
    // upside down: the +x end is the low one
    const Man f = capsule_plane(capsule(V(0.f, 0.f, 1.5f), V(0.f, 0.f, -1.f), 0.5f, 1.f), ground, 0.1f);
    REQUIRE(f.count == 1);
    CHECK(f.points[0].feature == 1u);
  }
  {  // tilted: ends at heights 1.4 and 2.6, gaps 0.9 and 2.1
    const Shape c = capsule(V(0.f, 0.f, 2.f), V(0.8f, 0.f, 0.6f), 0.5f, 1.f);
    const Man m = capsule_plane(c, ground, 1.f);
    REQUIRE(m.count == 1);
    check_point(m, 0, V(-0.8f, 0.f, 0.45f), 0.9f, 0u);
    const Man both = capsule_plane(c, ground, 3.f);
    REQUIRE(both.count == 2);
    check_point(both, 1, V(0.8f, 0.f, 1.05f), 2.1f, 1u);
    CHECK(capsule_plane(c, ground, 0.9f).count == 0);
  }
  {  // tilted plane n = (0, 0.6, 0.8), d = 2; capsule along x lying on it, gap 0.25
    const V n(0.f, 0.6f, 0.8f);
    const Man m = capsule_plane(capsule(V(2.75f * n), V(1.f, 0.f, 0.f), 0.5f, 1.f), plane(n, 2.f), 0.3f);
    REQUIRE(m.count == 2);
    check_vec(m.n, n);
    check_point(m, 0, V(V(-1.f, 0.f, 0.f) + 2.125f * n), 0.25f, 0u);
    check_point(m, 1, V(V(1.f, 0.f, 0.f) + 2.125f * n), 0.25f, 1u);
  }
}

// ---------------------------------------------------------------- capsule-capsule

TEST_CASE("capsule-capsule: crossed at right angles, end to end, margin, swap", "[collision]") {
  const Shape a = capsule(V(0.f, 0.f, 1.f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
  const Shape b = capsule(V(0.f, 0.f, 0.f), V(0.f, 1.f, 0.f), 0.4f, 1.f);
  const Man m = capsule_capsule(a, b, 0.2f);
  REQUIRE(m.count == 1);
  check_vec(m.n, V(0.f, 0.f, 1.f));
  check_point(m, 0, V(0.f, 0.f, 0.45f), 0.1f, 8u);  // side against side
  CHECK(capsule_capsule(a, b, 0.09f).count == 0);
  CHECK(capsule_capsule(a, b, 0.11f).count == 1);
  CHECK(capsule_capsule(moved(a, V(0.f, 0.f, 5.f)), b, 0.2f).count == 0);
  const Man s = capsule_capsule(b, a, 0.2f);
  REQUIRE(s.count == 1);
  check_vec(s.n, V(0.f, 0.f, -1.f));
  check_vec(s.points[0].p, m.points[0].p);
  CHECK(s.points[0].gap == Approx(m.points[0].gap));
  // the features stay while the same features touch
  CHECK(features(capsule_capsule(moved(a, V(1e-3f, -2e-3f, 1e-3f)), b, 0.2f)) == features(m));

  // overlapping, crossed, centres coincident: normal across both axes
  const Man c = capsule_capsule(moved(a, V(0.f, 0.f, -1.f)), b, 0.f);
  REQUIRE(c.count == 1);
  CHECK(finite_unit(c.n));
  CHECK(std::fabs(c.n[2]) == Approx(1.f));
  CHECK(c.points[0].gap == Approx(-0.9f));

  // end to end along x: caps 0.05 apart, a's -x cap on b's +x cap
  const Shape e = capsule(V(2.05f, 0.f, 0.f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
  const Shape f = capsule(V(0.f, 0.f, 0.f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
  const Man ef = capsule_capsule(e, f, 0.f);
  REQUIRE(ef.count == 1);
  check_vec(ef.n, V(1.f, 0.f, 0.f));
  check_point(ef, 0, V(1.025f, 0.f, 0.f), -0.95f, 1u);  // 3 * cap 0 + cap 1

  // a 45 degree crossing, 1 point
  const Man d = capsule_capsule(capsule(V(0.f, 0.f, 1.f), V(1.f, 1.f, 0.f), 0.5f, 1.f), b, 0.2f);
  REQUIRE(d.count == 1);
  check_point(d, 0, V(0.f, 0.f, 0.45f), 0.1f, 8u);
}

TEST_CASE("capsule-capsule: lying side by side gives the overlap's two ends", "[collision]") {
  // parallel, offset: a spans x in [-0.5, 1.5] at z 0.9, b x in [-1, 1]: overlap [-0.5, 1]
  const Shape a = capsule(V(0.5f, 0.f, 0.9f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
  const Shape b = capsule(V(0.f, 0.f, 0.f), V(1.f, 0.f, 0.f), 0.4f, 1.f);
  {
    const Man m = capsule_capsule(a, b, 0.01f);
    REQUIRE(m.count == 2);
    check_vec(m.n, V(0.f, 0.f, 1.f));
    check_point(m, 0, V(-0.5f, 0.f, 0.4f), 0.f, 0u);
    check_point(m, 1, V(1.f, 0.f, 0.4f), 0.f, 1u);
    // swapped: turned normal, the same points and gaps (in some order)
    const Man s = capsule_capsule(b, a, 0.01f);
    REQUIRE(s.count == 2);
    check_vec(s.n, V(0.f, 0.f, -1.f));
    for (int k = 0; k < 2; ++k) {
      const bool found = (near(s.points[k].p, m.points[0].p) && std::fabs(s.points[k].gap - m.points[0].gap) < 1e-5f) ||
                         (near(s.points[k].p, m.points[1].p) && std::fabs(s.points[k].gap - m.points[1].gap) < 1e-5f);
      CHECK(found);
    }
    CHECK(distinct_features(s));
    // a tiny slide keeps the features; anti-parallel b too
    CHECK(features(capsule_capsule(moved(a, V(1e-3f, 1e-3f, -1e-3f)), b, 0.01f)) == features(m));
    const Man r = capsule_capsule(a, capsule(V(0.f, 0.f, 0.f), V(-1.f, 0.f, 0.f), 0.4f, 1.f), 0.01f);
    REQUIRE(r.count == 2);
    check_point(r, 0, V(-0.5f, 0.f, 0.4f), 0.f, 0u);
    check_point(r, 1, V(1.f, 0.f, 0.4f), 0.f, 1u);
  }
  {  // sunk by 0.1 and offset sideways in y: normal tilted, gaps -0.1
    const V off(0.f, 0.6f, 0.8f);
    const Man m = capsule_capsule(capsule(V(0.8f * off), V(1.f, 0.f, 0.f), 0.5f, 1.f), b, 0.f);
    REQUIRE(m.count == 2);
    check_vec(m.n, off);
    check_point(m, 0, V(V(-1.f, 0.f, 0.f) + 0.35f * off), -0.1f, 0u);
    check_point(m, 1, V(V(1.f, 0.f, 0.f) + 0.35f * off), -0.1f, 1u);
  }
  {  // b turned 5 degrees about z under a: overlap ends at x = -+cos 5 along a, both gaps 0.1
    const float th = 5.f * pi / 180.f, c = std::cos(th), s = std::sin(th);
    const Shape t = capsule(V(0.f, 0.f, 0.f), V(c, s, 0.f), 0.4f, 1.f);
    const Shape top = capsule(V(0.f, 0.f, 1.f), V(1.f, 0.f, 0.f), 0.5f, 1.f);
    const Man m = capsule_capsule(top, t, 0.2f);
    REQUIRE(m.count == 2);
    check_vec(m.n, V(0.f, 0.f, 1.f));
    // each end's partner on b: its projection, at c^2 along b
    check_point(m, 0, V(-c * c * c, -c * c * s, 0.45f), 0.1f, 0u);
    check_point(m, 1, V(c * c * c, c * c * s, 0.45f), 0.1f, 1u);
    // turned 20 degrees instead: no longer side by side, one point
    const float t20 = 20.f * pi / 180.f;
    CHECK(capsule_capsule(top, capsule(V(), V(std::cos(t20), std::sin(t20), 0.f), 0.4f, 1.f), 0.2f).count == 1);
  }
  {  // coincident parallel capsules: finite unit normal, all points overlapping by the radii
    const Man m = capsule_capsule(b, b, 0.f);
    REQUIRE(m.count >= 1);
    CHECK(finite_unit(m.n));
    CHECK(min_gap(m) == Approx(-0.8f));
  }
}

TEST_CASE("capsule-capsule gap matches brute-force sampling on random poses", "[collision]") {
  std::mt19937 rng(20240611u);
  std::uniform_real_distribution<float> uni(-1.f, 1.f);
  int checked = 0, two_point = 0;
  for (int it = 0; it < 150; ++it) {
    const V ua(uni(rng), uni(rng), uni(rng));
    V ub(uni(rng), uni(rng), uni(rng));
    if (norm(ua) < 0.1f || norm(ub) < 0.1f) continue;
    if (it % 3 == 0) ub = V(ua + 0.05f * ub);  // nearly parallel: the two-point path
    const Shape a = capsule(V(uni(rng), uni(rng), uni(rng)), ua, 0.1f + 0.2f * (uni(rng) + 1.f), 0.3f + 0.5f * (uni(rng) + 1.f));
    const Shape b = capsule(V(uni(rng), uni(rng), uni(rng)), ub, 0.1f + 0.2f * (uni(rng) + 1.f), 0.2f + 0.5f * (uni(rng) + 1.f));
    const V a0 = a.x - a.p[1] * a.axis(0), a1 = a.x + a.p[1] * a.axis(0);
    const V b0 = b.x - b.p[1] * b.axis(0), b1 = b.x + b.p[1] * b.axis(0);
    const double want = brute_segments(d3(a0), d3(a1), d3(b0), d3(b1)) - a.p[0] - b.p[0];
    const Man m = capsule_capsule(a, b, 100.f);
    INFO("case " << it);
    REQUIRE(m.count >= 1);
    CHECK(finite_unit(m.n));
    CHECK(distinct_features(m));
    CHECK(min_gap(m) == Approx(want).margin(2e-3));
    const Man s = capsule_capsule(b, a, 100.f);
    REQUIRE(s.count == m.count);
    CHECK(near(s.n, V(-m.n), 1e-4f));
    CHECK(min_gap(s) == Approx(min_gap(m)).margin(1e-4));
    ++checked;
    two_point += m.count == 2;
  }
  CHECK(checked > 100);
  CHECK(two_point > 20);
}

// ---------------------------------------------------------------- capsule-box

// A box turned and moved, so that the local answers below are mapped to the world.
const M box_R = rotation(V(0.3f, -0.5f, 0.8f), 0.7f);
const Shape test_box = box(V(0.5f, -1.f, 2.f), box_R, 1.f, 0.5f, 0.25f);

Shape capsule_in_box(const V& local_x, const V& local_dir, float r, float L) {
  return capsule(test_box.to_world(local_x), V(box_R * local_dir), r, L);
}
V world(const V& local) { return test_box.to_world(local); }
V world_dir(const V& local) { return V(box_R * local); }

TEST_CASE("capsule-box: lying flat on a face gives 2 points with exact gaps", "[collision]") {
  for (float g : {0.f, -0.05f, 0.03f}) {
    const Man m = capsule_box(capsule_in_box(V(0.1f, 0.f, 0.45f + g), V(1.f, 0.f, 0.f), 0.2f, 0.6f), test_box, 0.05f);
    INFO("gap " << g);
    REQUIRE(m.count == 2);
    check_vec(m.n, world_dir(V(0.f, 0.f, 1.f)));
    check_point(m, 0, world(V(-0.5f, 0.f, 0.25f + g / 2)), g, 0u);
    check_point(m, 1, world(V(0.7f, 0.f, 0.25f + g / 2)), g, 1u);
  }
  // hanging over the +x edge: clipped to the face, x in [0.4, 1]
  const Shape over = capsule_in_box(V(1.f, 0.1f, 0.45f), V(1.f, 0.f, 0.f), 0.2f, 0.6f);
  const Man m = capsule_box(over, test_box, 0.05f);
  REQUIRE(m.count == 2);
  check_point(m, 0, world(V(0.4f, 0.1f, 0.25f)), 0.f, 0u);
  check_point(m, 1, world(V(1.f, 0.1f, 0.25f)), 0.f, 1u);
  CHECK(features(capsule_box(moved(over, world_dir(V(1e-3f, 2e-3f, 0.f))), test_box, 0.05f)) == features(m));
  // the core sunk into the face (r 0.2, 0.3 deep): still 2 points, along the face normal
  const Man d = capsule_box(capsule_in_box(V(0.f, 0.f, 0.15f), V(1.f, 0.f, 0.f), 0.2f, 0.6f), test_box, 0.f);
  REQUIRE(d.count == 2);
  check_vec(d.n, world_dir(V(0.f, 0.f, 1.f)));
  check_point(d, 0, world(V(-0.6f, 0.f, 0.1f)), -0.3f, 0u);
  check_point(d, 1, world(V(0.6f, 0.f, 0.1f)), -0.3f, 1u);
  // tilted 3 degrees: the two ends have their own gaps
  const float th = 3.f * pi / 180.f;
  const V u(std::cos(th), 0.f, std::sin(th));
  const Man t = capsule_box(capsule_in_box(V(0.f, 0.f, 0.45f + 0.6f * u[2]), u, 0.2f, 0.6f), test_box, 0.1f);
  REQUIRE(t.count == 2);
  check_point(t, 0, world(V(-0.6f * u[0], 0.f, 0.25f)), 0.f, 0u);
  check_point(t, 1, world(V(0.6f * u[0], 0.f, 0.25f + 0.6f * u[2])), 1.2f * u[2], 1u);
  CHECK(capsule_box(capsule_in_box(V(0.f, 0.f, 0.45f + 0.6f * u[2]), u, 0.2f, 0.6f), test_box, 0.05f).count == 1);
}

TEST_CASE("capsule-box: standing on a face, tilted on its end: 1 point", "[collision]") {
  for (float g : {0.02f, -0.1f, -0.3f}) {  // -0.3: the core is inside the box
    INFO("gap " << g);
    const Shape c = capsule_in_box(V(0.3f, 0.1f, 1.05f + g), V(0.f, 0.f, 1.f), 0.2f, 0.6f);
    const Man m = capsule_box(c, test_box, 0.05f);
    REQUIRE(m.count == 1);
    check_vec(m.n, world_dir(V(0.f, 0.f, 1.f)));
    check_point(m, 0, world(V(0.3f, 0.1f, 0.25f + g / 2)), g, 0u);
    CHECK(features(capsule_box(moved(c, world_dir(V(1e-3f, 1e-3f, 1e-3f))), test_box, 0.05f)) == features(m));
    const Man f = capsule_box(capsule_in_box(V(0.3f, 0.1f, 1.05f + g), V(0.f, 0.f, -1.f), 0.2f, 0.6f), test_box, 0.05f);
    REQUIRE(f.count == 1);
    CHECK(f.points[0].feature == 1u);  // upside down: the +x end stands on the face
  }
  // tilted 30 degrees, resting on its lower end
  const float c30 = std::cos(pi / 6), s30 = 0.5f;
  const Man m = capsule_box(capsule_in_box(V(0.f, 0.f, 0.45f + 0.02f + 0.3f), V(c30, 0.f, s30), 0.2f, 0.6f), test_box, 0.05f);
  REQUIRE(m.count == 1);
  check_vec(m.n, world_dir(V(0.f, 0.f, 1.f)));
  check_point(m, 0, world(V(-0.6f * c30, 0.f, 0.26f)), 0.02f, 0u);
  // apart beyond the margin
  CHECK(capsule_box(capsule_in_box(V(0.3f, 0.1f, 1.2f), V(0.f, 0.f, 1.f), 0.2f, 0.6f), test_box, 0.05f).count == 0);
}

TEST_CASE("capsule-box: across an edge, beside a side face", "[collision]") {
  const float r2 = std::sqrt(0.5f);
  const V edge(1.f, 0.f, 0.25f);   // on the edge along y at x = 1, z = 0.25
  const V out(r2, 0.f, r2);        // the edge's outward bisector
  const V across(r2, 0.f, -r2);    // the capsule's axis, crossing the edge
  {  // the core 0.25 from the edge, r 0.2: gap 0.05
    const Shape c = capsule_in_box(V(edge + 0.25f * out), across, 0.2f, 1.f);
    const Man m = capsule_box(c, test_box, 0.1f);
    REQUIRE(m.count == 1);
    check_vec(m.n, world_dir(out));
    check_point(m, 0, world(V(edge + 0.025f * out)), 0.05f, 2u);
    CHECK(features(capsule_box(moved(c, world_dir(V(0.f, 1e-3f, 1e-3f))), test_box, 0.1f)) == features(m));
  }
  {  // the core 0.05 into the edge: the edge axis, gap -0.25
    const Man m = capsule_box(capsule_in_box(V(edge - 0.05f * out), across, 0.2f, 1.f), test_box, 0.f);
    REQUIRE(m.count == 1);
    check_vec(m.n, world_dir(out), 1e-4f);
    check_point(m, 0, world(V(edge - 0.125f * out)), -0.25f, 2u, 1e-4f);
  }
  {  // standing beside the +x face (taller than it): clipped to z in [-0.25, 0.25]
    const Shape c = capsule_in_box(V(1.2f, 0.1f, 0.f), V(0.f, 0.f, 1.f), 0.2f, 0.6f);
    const Man m = capsule_box(c, test_box, 0.05f);
    REQUIRE(m.count == 2);
    check_vec(m.n, world_dir(V(1.f, 0.f, 0.f)));
    check_point(m, 0, world(V(1.f, 0.1f, -0.25f)), 0.f, 0u);
    check_point(m, 1, world(V(1.f, 0.1f, 0.25f)), 0.f, 1u);
  }
  {  // lying along y beside the +x face, 0.05 apart
    const Man m = capsule_box(capsule_in_box(V(1.25f, 0.f, 0.1f), V(0.f, 1.f, 0.f), 0.2f, 0.3f), test_box, 0.1f);
    REQUIRE(m.count == 2);
    check_vec(m.n, world_dir(V(1.f, 0.f, 0.f)));
    check_point(m, 0, world(V(1.025f, -0.3f, 0.1f)), 0.05f, 0u);
    check_point(m, 1, world(V(1.025f, 0.3f, 0.1f)), 0.05f, 1u);
    CHECK(capsule_box(capsule_in_box(V(1.25f, 0.f, 0.1f), V(0.f, 1.f, 0.f), 0.2f, 0.3f), test_box, 0.04f).count == 0);
  }
  {  // through the box's centre, along x and along a diagonal: finite unit normals
    for (const V dir : {V(1.f, 0.f, 0.f), V(1.f, 1.f, 1.f), V(0.f, 0.f, 1.f)}) {
      const Man m = capsule_box(capsule_in_box(V(), dir, 0.2f, 0.5f), test_box, 0.f);
      REQUIRE(m.count >= 1);
      CHECK(finite_unit(m.n));
      CHECK(distinct_features(m));
      for (int k = 0; k < m.count; ++k) CHECK(m.points[k].gap < -0.2f);
    }
  }
}

TEST_CASE("capsule-box gap matches brute-force sampling on random separated poses", "[collision]") {
  std::mt19937 rng(7771u);
  std::uniform_real_distribution<float> uni(-1.f, 1.f);
  int separated = 0, penetrating = 0;
  for (int it = 0; it < 400; ++it) {
    const V axis(uni(rng), uni(rng), uni(rng));
    if (norm(axis) < 0.1f) continue;
    const Shape bx = box(V(uni(rng), uni(rng), uni(rng)), rotation(axis, 3.f * uni(rng)), 0.2f + 0.4f * (uni(rng) + 1.f),
                         0.2f + 0.4f * (uni(rng) + 1.f), 0.2f + 0.4f * (uni(rng) + 1.f));
    V dir(uni(rng), uni(rng), uni(rng));
    if (norm(dir) < 0.1f) continue;
    if (it % 4 == 1) dir = V(bx.R * V(1.f, 0.3f * uni(rng), 0.05f * uni(rng)));  // nearly along a face
    const Shape c = capsule(V(bx.x + 2.f * V(uni(rng), uni(rng), uni(rng))), dir, 0.05f + 0.2f * (uni(rng) + 1.f),
                            0.1f + 0.5f * (uni(rng) + 1.f));
    const V p0 = bx.to_local(V(c.x - c.p[1] * c.axis(0))), p1 = bx.to_local(V(c.x + c.p[1] * c.axis(0)));
    const double h[3] = {bx.p[0], bx.p[1], bx.p[2]};
    const double core = brute_segment_box(d3(p0), d3(p1), h);
    const Man m = capsule_box(c, bx, 100.f);
    INFO("case " << it << ", core distance " << core);
    REQUIRE(m.count >= 1);
    CHECK(finite_unit(m.n));
    CHECK(distinct_features(m));
    if (core > 1e-3) {
      // exact, also for a core just beside a face and nearly parallel to it,
      // taken as lying on it (its end beside the face keeps its own gap)
      CHECK(min_gap(m) == Approx(core - c.p[0]).margin(2e-5));
      ++separated;
    } else {
      CHECK(min_gap(m) <= -c.p[0] + 1.1e-3f);
      ++penetrating;
    }
  }
  CHECK(separated > 200);
  CHECK(penetrating > 10);
}

TEST_CASE("capsule pairs in double precision", "[collision]") {
  using Vd = gpusolve::math::Vector3<double>;
  using Md = gpusolve::math::Matrix3x3<double>;
  const PlacedShape<double> a{Vd(0.5, 0.0, 0.9), Md::identity(), {0.5, 1.0, 0.0, 0.0}};
  const PlacedShape<double> b{Vd(0.0, 0.0, 0.0), Md::identity(), {0.4, 1.0, 0.0, 0.0}};
  const Manifold<double> m = capsule_capsule(a, b, 0.01);
  REQUIRE(m.count == 2);
  CHECK(m.points[0].gap == Approx(0.0).margin(1e-12));
  const PlacedShape<double> bx{Vd(0.0, 0.0, 0.0), Md::identity(), {1.0, 0.5, 0.25, 0.0}};
  const Manifold<double> f = capsule_box(a, bx, 0.3);
  REQUIRE(f.count == 2);
  CHECK(f.points[0].gap == Approx(0.15).margin(1e-12));
  const PlacedShape<double> ground{Vd(), Md::identity(), {0.0, 0.0, 1.0, 0.0}};
  CHECK(capsule_plane(a, ground, 0.5).count == 2);
  const PlacedShape<double> s{Vd(0.0, 0.0, 2.0), Md::identity(), {0.5, 0.0, 0.0, 0.0}};
  CHECK(sphere_capsule(s, b, 1.2).points[0].gap == Approx(1.1).margin(1e-12));
}

}  // namespace pairs_capsule_test
}  // namespace
