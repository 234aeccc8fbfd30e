// Broad phase against brute force, narrow-phase geometry by hand, and the contact list.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <string>
#include <type_traits>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/collision/collision_detection.hpp"
#include "test_rbd_collision_scene.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;
using V = math::Vector3<float>;
using M = math::Matrix3x3<float>;

namespace {

std::vector<std::uint64_t> grid_pairs(BodySet<float>& s, float margin) {
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  UniformGrid<device::cpu> grid;
  const std::size_t n = grid.find_pairs(m.device(), margin);
  REQUIRE(n == grid.count());
  // The grid pairs bounding spheres; keep the sphere pairs, which brute force lists.
  std::vector<std::uint64_t> spheres;
  for (std::size_t k = 0; k < n; ++k)
    if (s[pair_a(grid.pairs()[k])].shape == sphere && s[pair_b(grid.pairs()[k])].shape == sphere)
      spheres.push_back(grid.pairs()[k]);
  return spheres;
}

void require_vec(const V& v, float x, float y, float z, float eps = 1e-5f) {
  CHECK(v[0] == Approx(x).margin(eps));
  CHECK(v[1] == Approx(y).margin(eps));
  CHECK(v[2] == Approx(z).margin(eps));
}

// A one-point manifold's point as a contact: normal, gap and the offset ra
// from body a's centre.
struct OnePoint {
  V n, ra;
  float gap;
};
OnePoint one(const Manifold<float>& m, const V& pa) {
  REQUIRE(m.count == 1);
  return {m.n, V(m.points[0].p - pa), m.points[0].gap};
}
PlacedShape<float> placed_box(const V& x, const M& R, const V& h) { return {x, R, {h[0], h[1], h[2], 0.f}}; }

}  // namespace

TEST_CASE("uniform grid finds exactly the brute-force sphere pairs", "[rbd][collision]") {
  for (unsigned seed : {1u, 2u, 3u})
    for (int n : {1, 2, 60, 700, 2500})
      for (float margin : {0.f, 0.05f}) {
        // Dense enough that most spheres have neighbours, sparse enough to spread over many cells.
        BodySet<float> s = rbd_test::random_cloud(seed, n, 1.2f * std::cbrt(float(n)) + 1.f);
        const auto expected = rbd_test::brute_force_pairs(s, margin);
        INFO("seed " << seed << ", n " << n << ", margin " << margin);
        CHECK(grid_pairs(s, margin) == expected);
        if (n >= 700) CHECK(expected.size() > std::size_t(n) / 4);  // the cloud really has contacts
      }
}

TEST_CASE("uniform grid handles spheres straddling cell boundaries and far from the origin",
          "[rbd][collision]") {
  BodySet<float> s;
  // Cell size is 2 * 0.5 = 1: centres at -0.49 and 0.49 sit in cells -1 and 0 and
  // touch across the boundary; a chain along a diagonal crosses cells in x, y and z.
  s.add_sphere({-0.49f, 0.f, 0.f}, 0.5f, 1.f);
  s.add_sphere({0.49f, 0.f, 0.f}, 0.5f, 1.f);
  for (int k = 0; k < 6; ++k) s.add_sphere({1000.f + 0.55f * k, -2000.f + 0.55f * k, 0.55f * k}, 0.5f, 1.f);
  const auto expected = rbd_test::brute_force_pairs(s, 0.f);
  REQUIRE(expected.size() == 6);  // one boundary pair and five chain links
  CHECK(grid_pairs(s, 0.f) == expected);
}

TEST_CASE("sphere resting on a plane: gap 0, normal = plane normal", "[rbd][collision]") {
  const V n(0.f, 0.6f, 0.8f);  // a tilted unit normal
  const float d = 2.f;
  const V pa = (d + 1.5f) * n;  // centre 1.5 above the plane
  const auto g = one(sphere_plane(pa, 1.5f, n, d), pa);
  CHECK(g.gap == Approx(0.f).margin(1e-6));
  require_vec(g.n, 0.f, 0.6f, 0.8f);
  require_vec(g.ra, 0.f, -0.9f, -1.2f);  // from the centre down to the plane
  const auto lifted = sphere_plane(V(pa + 0.25f * n), 1.5f, n, d);
  CHECK(lifted.points[0].gap == Approx(0.25f));
  const auto sunk = sphere_plane(V(pa - 0.5f * n), 1.5f, n, d);
  CHECK(sunk.points[0].gap == Approx(-0.5f));
  // The table's entry keeps the point only below the margin.
  const PlacedShape<float> ball{V(pa + 0.25f * n), M::identity(), {1.5f, 0.f, 0.f, 0.f}};
  const PlacedShape<float> floor{V(), M::identity(), {n[0], n[1], n[2], d}};
  CHECK(sphere_plane(ball, floor, 0.2f).count == 0);
  CHECK(sphere_plane(ball, floor, 0.3f).count == 1);
}

TEST_CASE("sphere-sphere geometry", "[rbd][collision]") {
  const V pa(1.f, 2.f, 3.f), pb(1.f, 2.f + 0.6f, 3.f + 0.8f);  // one unit apart
  const auto g = one(sphere_sphere(pa, 0.3f, pb, 0.5f), pa);
  CHECK(g.gap == Approx(0.2f));
  require_vec(g.n, 0.f, -0.6f, -0.8f);  // from b to a
  // The contact point lies midway between the two surfaces.
  require_vec(g.ra, 0.f, 0.6f * 0.4f, 0.8f * 0.4f);
}

TEST_CASE("sphere-box geometry: face, edge, corner, inside, rotated", "[rbd][collision]") {
  const V pb(1.f, 1.f, 1.f), h(1.f, 2.f, 3.f);
  const M I = M::identity();
  SECTION("face") {
    const V pa(1.f, 1.f + 2.f + 0.7f, 1.5f);
    const auto g = one(sphere_box(pa, 0.5f, placed_box(pb, I, h)), pa);
    CHECK(g.gap == Approx(0.2f));
    require_vec(g.n, 0.f, 1.f, 0.f);
  }
  SECTION("edge") {
    const float s = 1.f / std::sqrt(2.f);
    const V pa(1.f + 1.f + s, 1.f + 2.f + s, 1.f);  // 1 from the edge x = 1, y = 2
    const auto g = one(sphere_box(pa, 0.25f, placed_box(pb, I, h)), pa);
    CHECK(g.gap == Approx(0.75f));
    require_vec(g.n, s, s, 0.f);
  }
  SECTION("corner") {
    const float s = 1.f / std::sqrt(3.f);
    const V pa(1.f - 1.f - 2 * s, 1.f + 2.f + 2 * s, 1.f - 3.f - 2 * s);  // 2 from the corner
    const auto g = one(sphere_box(pa, 2.f, placed_box(pb, I, h)), pa);
    CHECK(g.gap == Approx(0.f).margin(1e-5));
    require_vec(g.n, -s, s, -s);
  }
  SECTION("centre inside: pushed out through the nearest face") {
    const V pa(1.f + 0.8f, 1.f, 1.f);  // 0.2 from the +x face, farther from all others
    const auto g = one(sphere_box(pa, 0.5f, placed_box(pb, I, h)), pa);
    CHECK(g.gap == Approx(-0.7f));
    require_vec(g.n, 1.f, 0.f, 0.f);
  }
  SECTION("rotated box") {
    // 90 degrees about z: the box's x half extent (1) now lies along world y.
    const M R = math::to_rotation_matrix(math::Quaternion<float>(std::sqrt(0.5f), 0.f, 0.f, std::sqrt(0.5f)));
    const V pa(1.f, 1.f + 1.f + 0.5f, 1.f);
    const auto g = one(sphere_box(pa, 0.25f, placed_box(pb, R, h)), pa);
    CHECK(g.gap == Approx(0.25f));
    require_vec(g.n, 0.f, 1.f, 0.f);
  }
}

TEST_CASE("collision detection: margin, fixed pairs, obstacles, tangents, order", "[rbd][collision]") {
  BodySet<float> s;
  s.add_fixed_box({0.f, 0.f, -10.f}, {1.f, 1.f, 1.f});      // 0: far below everything
  s.add_sphere({0.f, 0.f, 3.05f}, 1.f, 1.f);          // 1: 0.05 above sphere 2
  s.add_sphere({0.f, 0.f, 1.f}, 1.f, 1.f);            // 2: resting on the plane
  s.add_plane({0.f, 0.f, 1.f}, 0.f);                  // 3
  s.add_fixed_sphere({5.f, 0.f, 1.f}, 1.f);           // 4: fixed, on the plane, touching 5
  s.add_fixed_sphere({7.f, 0.f, 1.f}, 1.f);           // 5: fixed
  s.add_sphere({20.f, 0.f, 1.5f}, 1.f, 1.f);          // 6: 0.5 above the plane: beyond the margin
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  CollisionDetection<device::cpu> cd;
  Contacts<device::cpu, float, PyramidFriction> c;
  const std::size_t n = cd.detect(m.device(), c, 0.1f, 0.4f);
  // (1,2) within the margin, (1,3) is 2.05 above the plane: none; (2,3) touching;
  // 4 and 5 both fixed: none; 6 too far.
  REQUIRE(n == 2);
  REQUIRE(c.size() == 2);
  CHECK(c.a(0) == 1u);
  CHECK(c.b(0) == 2u);
  CHECK(c.phi0(0) == Approx(0.05f));
  CHECK(c.n(0, 2) == Approx(1.f));
  CHECK(c.a(1) == 2u);
  CHECK(c.b(1) == 3u);
  CHECK(c.phi0(1) == Approx(0.f).margin(1e-6));
  for (std::size_t k = 0; k < n; ++k) {
    CHECK(c.mu(k) == Approx(0.4f));
    float tn = 0, on = 0, to = 0, tt = 0, oo = 0;
    for (int d = 0; d < 3; ++d) {
      tn += c.t(k, d) * c.n(k, d), on += c.o(k, d) * c.n(k, d), to += c.t(k, d) * c.o(k, d);
      tt += c.t(k, d) * c.t(k, d), oo += c.o(k, d) * c.o(k, d);
    }
    CHECK(tn == Approx(0.f).margin(1e-6));
    CHECK(on == Approx(0.f).margin(1e-6));
    CHECK(to == Approx(0.f).margin(1e-6));
    CHECK(tt == Approx(1.f));
    CHECK(oo == Approx(1.f));
  }
  CHECK_THROWS_AS(cd.detect(m.device(), c, -1.f), InvalidArgumentError);
}

TEST_CASE("collision detection on a random cloud matches a brute-force contact search", "[rbd][collision]") {
  const float margin = 0.02f;
  BodySet<float> s = rbd_test::random_cloud(7, 1500, 13.f);
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  CollisionDetection<device::cpu> cd;
  Contacts<device::cpu, float, Frictionless> c;
  const std::size_t n = cd.detect(m.device(), c, margin);
  // Expected: sphere pairs with an active partner, and active spheres near an obstacle.
  std::vector<std::uint64_t> expected;
  for (std::uint64_t k : rbd_test::brute_force_pairs(s, margin)) {
    const auto i = std::size_t(k >> 32), j = std::size_t(k & 0xffffffffu);
    if (s[i].status == active || s[j].status == active) expected.push_back(k);
  }
  auto& d = m.device();
  const BodyOffsets<float> off(d.view());
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i].shape != sphere || s[i].status != active) continue;
    const V pa(s[i].pos[0], s[i].pos[1], s[i].pos[2]);
    for (std::size_t j = 0; j < s.size(); ++j) {
      const auto& o = s[j];
      const V pb(o.pos[0], o.pos[1], o.pos[2]);
      float gap = 1e30f;
      if (o.shape == plane)
        gap = sphere_plane(pa, s[i].shape_param[0], V(o.shape_param[0], o.shape_param[1], o.shape_param[2]),
                           o.shape_param[3]).points[0].gap;
      if (o.shape == box)
        gap = sphere_box(pa, s[i].shape_param[0],
                         placed_box(pb, math::to_rotation_matrix(math::Quaternion<float>(o.q[0], o.q[1], o.q[2], o.q[3])),
                                    V(o.shape_param[0], o.shape_param[1], o.shape_param[2])))
                  .points[0].gap;
      if (gap < margin) expected.push_back((std::uint64_t(i) << 32) | j);
    }
  }
  std::sort(expected.begin(), expected.end());
  REQUIRE(expected.size() > 300);
  // Both ways of the write pass: spheres within the count pass's kept list and
  // a large sphere with more contacts, which walks the grid again.
  std::vector<std::size_t> per_sphere(s.size(), 0);
  for (std::uint64_t k : expected) ++per_sphere[std::size_t(k >> 32)];
  REQUIRE(*std::max_element(per_sphere.begin(), per_sphere.end()) > rbd::detail::kept_contacts);
  REQUIRE(n == expected.size());
  for (std::size_t k = 0; k < n; ++k) {
    INFO("contact " << k);
    REQUIRE(((std::uint64_t(c.a(k)) << 32) | c.b(k)) == expected[k]);  // also proves the (a, b) order
    CHECK(c.phi0(k) < margin);
  }
}

TEST_CASE("contacts that cannot grow throw OutOfMemoryError naming the contacts and the bytes", "[rbd][collision]") {
  Contacts<device::cpu, float, ConeFriction> c(8);
  try {
    c.resize(std::numeric_limits<std::size_t>::max() / 8);
    FAIL("no OutOfMemoryError");
  } catch (const OutOfMemoryError& e) {
    CHECK(std::string(e.what()).find("bytes for contacts") != std::string::npos);
  }
  CHECK(c.size() == 8);  // the failed growth left the count and the capacity as they were
  CHECK(c.capacity() == 8);
}

TEST_CASE("a detection's graph key has the same bytes for the same launches, whatever its storage held",
          "[rbd][collision]") {
  // GraphReplay launches the kept graph again only while the key's bytes are
  // those of the capture; padding left as it was would capture anew.
  BodySet<float> s;
  s.add_box({0.f, 0.f, 1.f}, {1.f, 1.f, 1.f}, 1.f);
  s.add_plane({0.f, 0.f, 1.f}, 0.f);
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  Contacts<device::cpu, float, ConeFriction> c;
  c.resize(8);
  const auto b = m.device().view();
  const auto cv = c.view();
  using Key = rbd::detail::DetectionKey<std::remove_const_t<decltype(b)>, std::remove_const_t<decltype(cv)>, float>;
  const ContactDefaults<float> defaults({0.5f, 0.f, 0.f, 0.f}, 1.f, 0.0025f);
  std::uint32_t hold = 0;
  alignas(Key) unsigned char zeros[sizeof(Key)], ones[sizeof(Key)];
  std::memset(zeros, 0x00, sizeof(Key));
  std::memset(ones, 0xff, sizeof(Key));
  const Key* first = new (zeros) Key{b, cv, 0.1f, defaults, &hold, m.device().shapes};
  const Key* second = new (ones) Key{b, cv, 0.1f, defaults, &hold, m.device().shapes};
  CHECK(std::memcmp(first, second, sizeof(Key)) == 0);
}
