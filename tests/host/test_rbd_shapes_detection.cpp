// Collision detection with every shape: the shape-pair table against its
// reversed pairs, and the contacts of a mixed heap against a brute-force
// search over all pairs through the table.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "catch_compat.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

using SV = math::Vector3<float>;
using M3 = math::Matrix3x3<float>;

// A random primitive of kind k near the origin, turned at random.
PlacedShape<float> random_shape(ShapeKind k, std::mt19937& gen) {
  std::uniform_real_distribution<float> u(-1.f, 1.f), size(0.2f, 0.8f);
  PlacedShape<float> s{SV(u(gen), u(gen), u(gen)), M3::identity(), {size(gen), size(gen), size(gen), 0.f}};
  float q[4], len = 0;
  for (float& x : q) x = u(gen), len += x * x;
  len = std::sqrt(len);
  s.R = math::to_rotation_matrix(math::Quaternion<float>(q[0] / len, q[1] / len, q[2] / len, q[3] / len));
  if (k == plane) {
    const SV n(u(gen), u(gen), 1.f);
    const float l = math::norm(n);
    s = PlacedShape<float>{SV(), M3::identity(), {n[0] / l, n[1] / l, n[2] / l, u(gen) * 0.5f}};
  }
  return s;
}

using Found = std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>>;  // a, b, feature

// Every contact point of the bodies by the shape-pair table over all pairs, as
// (a, b, feature), sorted. The grid's cell is the largest reach of a moving
// body; a fixed body beyond it is an obstacle, whose contacts name the moving body first.
template <class View>
Found brute_force_contacts(const BodySet<float>& s, const View& v, float margin) {
  float cell = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i].status == active) cell = std::max(cell, 2 * v.radius[i] + margin);
  auto obstacle = [&](std::size_t i) { return s[i].shape == plane || 2 * v.radius[i] + margin > cell; };
  Found expected;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = 0; j < s.size(); ++j) {
      if (i == j || s[i].status == removed || s[j].status == removed) continue;
      if (s[i].status != active && s[j].status != active) continue;
      const bool grid_pair = !obstacle(i) && !obstacle(j);
      if (grid_pair ? j < i : obstacle(i)) continue;  // each pair once, as detection orders it
      for_each_manifold<all_shapes, float>(v, i, j, margin, [&](const Manifold<float>& mf) {
        for (int p = 0; p < mf.count; ++p) expected.emplace_back(std::uint32_t(i), std::uint32_t(j), mf.points[p].feature);
      });
    }
  std::sort(expected.begin(), expected.end());
  return expected;
}

// Detection's contacts as (a, b, feature), sorted, after checking that they
// come sorted by (a, b) and within the margin. Detection lists a pair's points
// in its manifold's order; they compare as sets within a pair.
template <class C>
Found detected_contacts(const C& c, std::size_t n, float margin) {
  Found found;
  for (std::size_t k = 0; k < n; ++k) found.emplace_back(c.a(k), c.b(k), c.feature(k));
  for (std::size_t k = 1; k < n; ++k) {
    INFO("contact " << k);
    REQUIRE(std::make_pair(c.a(k - 1), c.b(k - 1)) <= std::make_pair(c.a(k), c.b(k)));
    CHECK(c.phi0(k) < margin);
  }
  std::sort(found.begin(), found.end());
  return found;
}

// One detection of the bodies s on the CPU backend, beside the brute-force search's contacts.
struct DetectionBesideSearch {
  BodyManager<device::cpu> m;
  CollisionDetection<device::cpu> cd;
  Contacts<device::cpu, float, Frictionless> c;
  float margin;
  std::size_t n = 0;
  Found expected;
  DetectionBesideSearch(BodySet<float>& s, float margin_) : m(s), margin(margin_) {
    m.syncDevice();
    n = cd.detect(m.device(), c, margin);
    expected = brute_force_contacts(s, m.device().view(), margin);
  }
  Found found() const { return detected_contacts(c, n, margin); }
};

}  // namespace

TEST_CASE("every shape pair of the table equals its reversed pair with the normal turned", "[collision][shapes]") {
  std::mt19937 gen(11);
  const ShapeKind kinds[] = {sphere, box, plane, capsule};
  std::size_t touching = 0;
  for (ShapeKind ka : kinds)
    for (ShapeKind kb : kinds) {
      if (ka == plane && kb == plane) continue;
      for (int trial = 0; trial < 300; ++trial) {
        const PlacedShape<float> a = random_shape(ka, gen), b = random_shape(kb, gen);
        const Manifold<float> ab = collide(ka, a, kb, b, 0.05f), ba = collide(kb, b, ka, a, 0.05f);
        INFO("kinds " << int(ka) << ", " << int(kb) << ", trial " << trial);
        REQUIRE((ab.count > 0) == (ba.count > 0));
        if (ab.count == 0) continue;
        ++touching;
        if (ka == kb) {
          // The same function with the bodies swapped: it may pick the other
          // body's face as the reference, so only the deepest gap must agree.
          auto deepest = [](const Manifold<float>& m) {
            float d = m.points[0].gap;
            for (int p = 1; p < m.count; ++p) d = std::min(d, m.points[p].gap);
            return d;
          };
          CHECK(deepest(ab) == Approx(deepest(ba)).epsilon(0.05).margin(2e-3));
          continue;
        }
        REQUIRE(ab.count == ba.count);
        CHECK(math::norm(ab.n) == Approx(1.f).margin(1e-5));
        for (int c = 0; c < 3; ++c) CHECK(ab.n[c] == Approx(-ba.n[c]).margin(1e-5));
        for (int p = 0; p < ab.count; ++p) {
          CHECK(ab.points[p].gap == Approx(ba.points[p].gap).margin(1e-5));
          CHECK(ab.points[p].feature == ba.points[p].feature);
          for (int c = 0; c < 3; ++c) CHECK(ab.points[p].p[c] == Approx(ba.points[p].p[c]).margin(1e-5));
        }
      }
    }
  CHECK(touching > 1000);  // most random pairs near the origin overlap
}

TEST_CASE("contacts of a mixed heap equal a brute-force search through the shape-pair table",
          "[collision][shapes]") {
  BodySet<float> s = mixed_heap<float>(5, 3);
  std::mt19937 gen(5);
  std::uniform_real_distribution<float> shake(-0.12f, 0.12f);
  for (std::size_t i = 1; i < s.size(); ++i)
    for (int c = 0; c < 3; ++c) s[i].pos[c] += shake(gen);  // pairs at every distance around the margin
  s.add_box({2.f, 2.f, 4.f}, {5.f, 0.5f, 0.5f}, 3.f);                    // a long moving box: the grid's cells follow it
  s.add_fixed_box({2.f, -9.f, 1.f}, {6.f, 6.f, 1.f});                    // fixed and larger: an obstacle
  s.add_fixed_capsule({1.f, 2.f, 0.3f}, 0.3f, 0.5f);                      // fixed, small: on the grid
  s.add_compound({8.f, 8.f, 6.f}, clump<float>(), 1.f);                   // two compounds whose parts touch
  s.add_compound({8.45f, 8.1f, 6.1f}, hammer<float>(), 1.f, {0.8f, 0.f, 0.6f, 0.f});
  s.add_compound({8.f, 2.f, 0.21f}, clump<float>(), 1.f);                  // on the plane, a box on it
  s.add_box({8.f, 2.f, 0.75f}, {0.3f, 0.3f, 0.3f}, 1.f);
  s[7].status = removed;
  const DetectionBesideSearch d(s, 0.05f);
  CHECK(d.found() == d.expected);
  // Every pair of kinds is among them (plane-plane aside), compounds too.
  std::array<std::array<std::size_t, shape_kinds>, shape_kinds> kinds{};
  for (const auto& e : d.expected) {
    const int ka = s[std::get<0>(e)].shape, kb = s[std::get<1>(e)].shape;
    ++kinds[std::min(ka, kb)][std::max(ka, kb)];
  }
  for (int ka = 0; ka < shape_kinds; ++ka)
    for (int kb = ka; kb < shape_kinds; ++kb) {
      INFO("kinds " << ka << ", " << kb << ": " << kinds[ka][kb] << " contacts");
      if (ka != plane || kb != plane) CHECK(kinds[ka][kb] > 0);
    }
}

TEST_CASE("a lattice of touching cubes, 13 candidate partners each, equals the brute-force search",
          "[collision][shapes]") {
  // Cubes of half extent 0.5 one apart: every face, edge and corner neighbour's
  // bounding sphere comes within the margin, past the pair passes' first list
  // (4 a body), so the list grows. Slightly turned, so that edges and corners
  // touch too.
  BodySet<float> s;
  s.add_plane({0.f, 0.f, 1.f}, 0.f);
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) {
        const float qx = 0.01f * float((x + y) % 3), qz = 0.01f * float(z % 2);
        s.add_box({float(x), float(y), 0.5f + float(z)}, {0.5f, 0.5f, 0.5f}, 1.f,
                  {std::sqrt(1.f - qx * qx - qz * qz), qx, 0.f, qz});
      }
  DetectionBesideSearch d(s, 0.05f);
  CHECK(d.expected.size() > 4 * s.size());
  CHECK(d.found() == d.expected);
  CHECK(d.cd.detect(d.m.device(), d.c, d.margin) == d.n);  // again, from the grown list
}

TEST_CASE("a box with more candidates than the count pass keeps lists them all from a second walk",
          "[collision][shapes]") {
  // A box of half extent 2 (body 0) with 16 cubes of half extent 0.5 on each
  // face, just apart: 96 partners past it, more than the walk keeps per body.
  BodySet<float> s;
  s.add_box({0.f, 0.f, 0.f}, {2.f, 2.f, 2.f}, 8.f);
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.f, 1.f})
      for (float u : {-1.5f, -0.5f, 0.5f, 1.5f})
        for (float w : {-1.5f, -0.5f, 0.5f, 1.5f}) {
          float x[3];
          x[axis] = side * 2.51f, x[(axis + 1) % 3] = u, x[(axis + 2) % 3] = w;
          s.add_box({x[0], x[1], x[2]}, {0.5f, 0.5f, 0.5f}, 1.f);
        }
  DetectionBesideSearch d(s, 0.05f);
  std::set<std::uint32_t> partners;
  for (const auto& [a, b, feature] : d.expected)
    if (a == 0) partners.insert(b);
  REQUIRE(partners.size() == 96);
  REQUIRE(partners.size() > rbd::detail::kept_candidates);
  CHECK(d.found() == d.expected);
}

TEST_CASE("a neighbour a box's slabs skip has no contact point with the box", "[collision][shapes]") {
  // Pairs far apart from each other: a box turned at random and a box or a
  // sphere, turned at random, placed where their bounding spheres come within
  // the margin (the grid's candidates). Wherever BoxSlabs says apart, the
  // shape-pair table finds no point; and it says so for a good share of such
  // pairs, or the filter would not pay.
  std::mt19937 gen(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f), size(0.2f, 0.8f);
  auto turn = [&] {
    float q[4], len = 0;
    for (float& x : q) x = u(gen), len += x * x;
    len = std::sqrt(len);
    return std::array<float, 4>{q[0] / len, q[1] / len, q[2] / len, q[3] / len};
  };
  const float margin = 0.05f;
  const std::size_t pairs = 20000;
  BodySet<float> s;
  for (std::size_t k = 0; k < pairs; ++k) {
    const float x0 = 10.f * float(k);
    const SV h(size(gen), size(gen), size(gen));
    s.add_box({x0, 0.f, 0.f}, {h[0], h[1], h[2]}, 1.f, turn());
    SV d(u(gen), u(gen), u(gen));
    const bool box = k % 2 == 0;
    const SV h1 = box ? SV(size(gen), size(gen), size(gen)) : SV(0.f, 0.f, 0.f);
    const float r1 = box ? math::norm(h1) : size(gen);
    d = d * ((math::norm(h) + r1 + margin) * (0.5f + 0.25f * (u(gen) + 1.f)) / math::norm(d));  // half the reach to all of it
    if (box)
      s.add_box({x0 + d[0], d[1], d[2]}, {h1[0], h1[1], h1[2]}, 1.f, turn());
    else
      s.add_sphere({x0 + d[0], d[1], d[2]}, r1, 1.f);
  }
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  const auto v = m.device().view();
  std::size_t skipped = 0, with_points = 0;
  for (std::size_t k = 0; k < pairs; ++k) {
    const std::size_t a = 2 * k, b = a + 1;
    std::size_t points = 0;
    for_each_manifold<all_shapes, float>(v, a, b, margin, [&](const Manifold<float>& mf) { points += std::size_t(mf.count); });
    with_points += points > 0;
    if (rbd::detail::BoxSlabs<float>(v, a).apart(rbd::detail::grid_sphere<decltype(v), float>(v, b), margin)) {
      ++skipped;
      INFO("pair " << k << " skipped, yet " << points << " points");
      CHECK(points == 0);
    }
  }
  INFO(pairs << " candidate pairs, " << with_points << " with points, " << skipped << " skipped");
  CHECK(with_points > pairs / 4);
  CHECK(skipped > pairs / 10);
}
