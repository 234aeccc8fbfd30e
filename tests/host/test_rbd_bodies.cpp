// BodySet validation (typed errors naming body and field, a compound's part among them) and BodyManager synchronisation.
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/bodies/body_manager.hpp"
#include "gpusolve/rbd/bodies/spatial_order.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;

namespace {

const float nan_f = std::numeric_limits<float>::quiet_NaN();
const float inf_f = std::numeric_limits<float>::infinity();

// Runs f, which must throw InvalidBodyError for `body` and `field`, with both in the message.
template <class F>
void require_bad(F&& f, std::size_t body, const std::string& field) {
  try {
    f();
    FAIL("no InvalidBodyError for field " << field);
  } catch (const InvalidBodyError& e) {
    CHECK(e.body() == body);
    CHECK(e.field() == field);
    const std::string what = e.what();
    CHECK(what.find("body " + std::to_string(body)) != std::string::npos);
    CHECK(what.find(field) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("BodySet builders derive mass properties", "[rbd][bodies]") {
  BodySet<float> s;
  const auto i = s.add_sphere({1.f, 2.f, 3.f}, 0.5f, 4.f);
  CHECK(s[i].inv_mass == Approx(0.25f));
  CHECK(s[i].inertia[0] == Approx(0.4f * 4.f * 0.25f));
  CHECK(s[i].inv_inertia_body[8] == Approx(1.f / (0.4f * 4.f * 0.25f)));
  CHECK(s[i].inertia[1] == 0.f);
  const auto p = s.add_plane({0.f, 3.f, 4.f}, 2.f);
  CHECK(s[p].status == fixed);
  CHECK(s[p].shape_param[1] == Approx(0.6f));
  CHECK(s[p].shape_param[2] == Approx(0.8f));
  CHECK(s[p].pos[2] == Approx(1.6f));
  const auto b = s.add_fixed_box({0.f, 0.f, 0.f}, {1.f, 2.f, 3.f});
  CHECK(s[b].inv_mass == 0.f);
  CHECK(s[b].status == fixed);
}

TEST_CASE("bad body input throws InvalidBodyError naming body and field", "[rbd][bodies]") {
  BodySet<float> s;
  s.add_sphere({0.f, 0.f, 0.f}, 1.f, 1.f);  // index 0 is fine; the bad ones would be index 1
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, 0.f, 1.f); }, 1, "radius");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, -1.f, 1.f); }, 1, "radius");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, nan_f, 1.f); }, 1, "radius");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, 1.f, 0.f); }, 1, "mass");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, 1.f, -2.f); }, 1, "mass");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, 1.f, inf_f); }, 1, "mass");
  require_bad([&] { s.add_sphere({0.f, 0.f, 0.f}, 1.f, 1.f, {1.f, -1.f, 1.f}); }, 1, "inertia");
  require_bad([&] { s.add_sphere({nan_f, 0.f, 0.f}, 1.f, 1.f); }, 1, "pos");
  require_bad([&] { s.add_fixed_box({0.f, 0.f, 0.f}, {1.f, 0.f, 1.f}); }, 1, "half_extents");
  require_bad([&] { s.add_fixed_box({0.f, 0.f, 0.f}, {1.f, 1.f, -1.f}); }, 1, "half_extents");
  require_bad([&] { s.add_fixed_box({0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, {2.f, 0.f, 0.f, 0.f}); }, 1, "q");
  require_bad([&] { s.add_plane({0.f, 0.f, 0.f}, 1.f); }, 1, "normal");
  require_bad([&] { s.add_plane({0.f, nan_f, 1.f}, 1.f); }, 1, "normal");
  require_bad([&] { s.add_fixed_sphere({0.f, 0.f, 0.f}, 0.f); }, 1, "radius");
  Body<float> b = s[0];
  b.v[2] = inf_f;
  require_bad([&] { s.add(b); }, 1, "v");
  b = s[0];
  b.w[0] = nan_f;
  require_bad([&] { s.add(b); }, 1, "w");
  b = s[0];
  b.status = fixed;  // fixed bodies must be massless
  require_bad([&] { s.add(b); }, 1, "mass");
  b = s[0];
  b.shape = plane;  // planes are always fixed
  b.shape_param = {0.f, 0.f, 1.f, 0.f};
  require_bad([&] { s.add(b); }, 1, "status");
  b = s[0];
  b.shape = capsule;
  b.shape_param = {0.5f, 0.f, 0.f, 0.f};
  require_bad([&] { s.add(b); }, 1, "half_length");
  require_bad([&] { s.add_box({0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, 0.f); }, 1, "mass");
  require_bad([&] { s.add_box({0.f, 0.f, 0.f}, {1.f, 1.f, nan_f}, 1.f); }, 1, "half_extents");
  require_bad([&] { s.add_box({0.f, 0.f, 0.f}, {1.f, 1.f, 1.f}, 1.f, {0.5f, 0.5f, 0.f, 0.f}); }, 1, "q");
  require_bad([&] { s.add_capsule({0.f, 0.f, 0.f}, 0.f, 1.f, 1.f); }, 1, "radius");
  require_bad([&] { s.add_capsule({0.f, 0.f, 0.f}, 0.5f, -1.f, 1.f); }, 1, "half_length");
  require_bad([&] { s.add_fixed_capsule({0.f, 0.f, 0.f}, 0.5f, 0.f); }, 1, "half_length");
  CHECK(s.size() == 1);  // nothing bad was added
  // State corrupted in place is caught at the next sync.
  s.add_sphere({0.f, 0.f, 5.f}, 1.f, 1.f);
  s[1].force[1] = nan_f;
  BodyManager<device::cpu> m(s);
  require_bad([&] { m.syncDevice(); }, 1, "force");
  CHECK(std::is_base_of_v<InvalidArgumentError, InvalidBodyError>);
}

TEST_CASE("BodyManager copies bodies and derived fields, and brings state back", "[rbd][bodies]") {
  BodySet<float> s;
  s.add_sphere({1.f, 2.f, 3.f}, 0.5f, 2.f);
  s.add_fixed_box({0.f, 0.f, 0.f}, {1.f, 2.f, 2.f}, {std::sqrt(0.5f), 0.f, 0.f, std::sqrt(0.5f)});
  s.add_plane({0.f, 0.f, 1.f}, -1.f);
  s[0].v = {1.f, 0.f, 0.f};
  BodyManager<device::cpu> m(s, 2);
  const SyncReport r = m.syncDevice();
  CHECK(r.bodies == 3);
  CHECK(r.full_from == 0);
  CHECK_FALSE(r.rebuilt);
  auto& d = m.device();
  REQUIRE(d.size() == 3);
  CHECK(d.pos(0, 2) == 3.f);
  CHECK(d.inv_mass(0) == Approx(0.5f));
  CHECK(d.radius(0) == 0.5f);
  CHECK(d.aabb(0, 0) == Approx(0.5f));
  CHECK(d.aabb(0, 5) == Approx(3.5f));
  CHECK(d.radius(1) == Approx(3.f));  // |(1, 2, 2)|
  CHECK(d.R(1, 1) == Approx(-1.f));   // 90 degrees about z: row 0 is (0, -1, 0)
  CHECK(std::isinf(d.radius(2)));
  CHECK(d.status(1) == fixed);
  // The device moves a body; syncHost brings it back into the records.
  d.pos(0, 0) = 7.f;
  d.v(0, 1) = -2.f;
  m.syncHost();
  CHECK(s[0].pos[0] == 7.f);
  CHECK(s[0].v[1] == -2.f);
}

TEST_CASE("BodyManager syncs more bodies than its staging holds, in a spatial order, with bodies added",
          "[rbd][bodies]") {
  // sync_chunk bodies pass through the host at a time: a sync of more must
  // give every body its own record, whatever chunk and slot it lands in.
  const std::size_t n = sync_chunk + 3000, added = 2000;
  BodySet<float> s;
  for (std::size_t i = 0; i < n; ++i) {
    s.add_sphere({0.001f * float(i), 1.f, 2.f}, 0.5f + 0.01f * float(i % 7), 1.f + float(i % 5));
    s[i].v = {float(i % 11), 0.f, 0.f};
  }
  BodyManager<device::cpu> m(s);
  m.syncDevice();
  auto& d = m.device();
  REQUIRE(d.size() == n);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < n; ++i)
    wrong += d.pos(i, 0) != s[i].pos[0] || d.v(i, 0) != s[i].v[0] || d.inv_mass(i) != s[i].inv_mass ||
             d.radius(i) != s[i].shape_param[0] || d.aabb(i, 3) != s[i].pos[0] + s[i].shape_param[0];
  CHECK(wrong == 0);
  // The device puts its bodies in reverse order, moves each by its record's index, and the records follow.
  std::vector<std::uint32_t> order(n);
  for (std::size_t k = 0; k < n; ++k) order[k] = std::uint32_t(n - 1 - k);
  SpatialOrder<device::cpu, float>::apply(d, order.data());
  m.reordered(order);
  for (std::size_t k = 0; k < n; ++k) d.pos(k, 1) = 1000.f + float(m.body(k));
  m.syncHost();
  wrong = 0;
  for (std::size_t i = 0; i < n; ++i) wrong += m.slot(i) != n - 1 - i || s[i].pos[1] != 1000.f + float(i);
  CHECK(wrong == 0);
  // Bodies added take the slots past the old end, whole; the old keep their
  // mass and take their records' state. The first addition grows the store
  // (every body copied whole), the second fits (the new from the middle of a chunk).
  for (std::size_t i = 0; i < added; ++i) m.bodyAdded(s.add_sphere({-1.f, -2.f, float(i)}, 0.25f, 8.f));
  CHECK(m.syncDevice().full_from == 0);
  for (std::size_t i = 0; i < added; ++i) m.bodyAdded(s.add_sphere({-1.f, -3.f, float(i)}, 0.25f, 8.f));
  s[7].v = {-3.f, 0.f, 0.f};
  CHECK(m.syncDevice().full_from == n + added);
  REQUIRE(d.size() == n + 2 * added);
  wrong = 0;
  for (std::size_t i = 0; i < n + 2 * added; ++i) {
    const std::size_t k = m.slot(i);
    wrong += (i >= n && k != i) || d.pos(k, 1) != s[i].pos[1] || d.pos(k, 2) != s[i].pos[2] ||
             d.v(k, 0) != s[i].v[0] || d.inv_mass(k) != s[i].inv_mass || d.radius(k) != s[i].shape_param[0];
  }
  CHECK(wrong == 0);
  CHECK(d.v(m.slot(7), 0) == -3.f);
}

TEST_CASE("BodyManager: lazy add, skipped leading bodies, removal threshold", "[rbd][bodies]") {
  BodySet<float> s;
  for (int i = 0; i < 4; ++i) s.add_sphere({float(i), 0.f, 0.f}, 0.25f, 1.f);
  BodyManager<device::cpu> m(s, 3);
  m.syncDevice();
  auto& d = m.device();
  // A device-only mark in a set-once field shows whether a body was copied again.
  d.shape_param(0, 1) = 42.f;
  d.shape_param(3, 1) = 42.f;

  SECTION("appended bodies: only they are copied in full") {
    m.bodyAdded(s.add_sphere({8.f, 0.f, 0.f}, 0.5f, 1.f));
    CHECK(m.syncDevice().full_from == 0);  // past the capacity of 4: reallocated, all copied
    CHECK(d.capacity() >= 6);
    d.shape_param(0, 1) = 42.f;
    s.add_sphere({9.f, 0.f, 0.f}, 0.75f, 1.f);
    m.bodyAdded(5);
    s[0].force = {0.f, 0.f, 5.f};  // per-step fields of every body are copied
    const SyncReport r = m.syncDevice();
    CHECK(r.full_from == 5);
    CHECK(r.bodies == 6);
    CHECK(d.shape_param(0, 1) == 42.f);  // leading body skipped
    CHECK(d.shape_param(5, 0) == 0.75f);
    CHECK(d.force(0, 2) == 5.f);
    CHECK(m.syncDeviceFull().full_from == 0);
    CHECK(d.shape_param(0, 1) == 0.f);  // full sync copies everything
  }
  SECTION("a body replaced in the middle is copied from there on") {
    s[2].shape_param[0] = 0.5f;
    m.bodyAdded(2);
    const SyncReport r = m.syncDevice();
    CHECK(r.full_from == 2);
    CHECK(d.shape_param(0, 1) == 42.f);
    CHECK(d.shape_param(3, 1) == 0.f);
    CHECK(d.radius(2) == 0.5f);
  }
  SECTION("growth past the capacity reallocates and copies all") {
    for (int i = 0; i < 100; ++i) m.bodyAdded(s.add_sphere({0.f, float(i), 5.f}, 0.25f, 1.f));
    const SyncReport r = m.syncDevice();
    CHECK(r.full_from == 0);
    CHECK(r.bodies == 104);
    CHECK(d.pos(103, 1) == 99.f);
  }
  SECTION("removals are marks until the threshold, then a compaction") {
    m.bodyRemoved(1);
    m.bodyRemoved(1);  // announcing twice counts once
    SyncReport r = m.syncDevice();
    CHECK_FALSE(r.rebuilt);
    CHECK(r.bodies == 4);
    CHECK(d.status(1) == removed);
    CHECK(s[1].status == removed);
    CHECK(m.removed_count() == 1);
    m.bodyRemoved(3);
    r = m.syncDevice();
    CHECK_FALSE(r.rebuilt);
    CHECK(m.removed_count() == 2);
    m.bodyRemoved(0);
    r = m.syncDevice();
    CHECK(r.rebuilt);
    CHECK(r.full_from == 0);
    REQUIRE(r.bodies == 1);
    REQUIRE(s.size() == 1);
    CHECK(s[0].pos[0] == 2.f);  // the survivor, body 2, is now body 0
    CHECK(d.pos(0, 0) == 2.f);
    CHECK(d.status(0) == active);
    CHECK(m.removed_count() == 0);
  }
  SECTION("bad indices and unannounced size changes") {
    m.bodyRemoved(17);
    CHECK_THROWS_AS(m.syncDevice(), InvalidArgumentError);
    s.add_sphere({0.f, 0.f, 0.f}, 1.f, 1.f);
    CHECK_THROWS_AS(m.syncHost(), SizeMismatchError);
  }
}

namespace {
// A sphere part of radius r centred at `at`.
Part<double> ball(double r, std::array<double, 3> at) { return {sphere, {r, 0, 0, 0}, at, {1, 0, 0, 0}}; }
}  // namespace

TEST_CASE("bad compound input names the body and the part's field, and adds nothing", "[rbd][bodies][compound]") {
  BodySet<double> set;
  set.add_sphere({0, 0, 0}, 1, 1);
  require_bad([&] { set.add_compound({0, 0, 0}, {}, 1.0); }, 1, "parts");
  require_bad([&] { set.add_compound({0, 0, 0}, {Part<double>{plane, {0, 0, 1, 0}, {}, {1, 0, 0, 0}}}, 1.0); }, 1,
              "parts[0].shape");
  require_bad([&] { set.add_compound({0, 0, 0}, {ball(1, {}), ball(-1, {1, 0, 0})}, 1.0); }, 1,
              "parts[1].radius");
  require_bad([&] { set.add_compound({0, 0, 0}, {Part<double>{box, {1, 0, 1, 0}, {}, {1, 0, 0, 0}}}, 1.0); }, 1,
              "parts[0].half_extents");
  require_bad([&] { set.add_compound({0, 0, 0}, {Part<double>{sphere, {1, 0, 0, 0}, {}, {2, 0, 0, 0}}}, 1.0); }, 1,
              "parts[0].q");
  require_bad([&] { set.add_compound({0, 0, 0}, {ball(1, {0, std::nan(""), 0})}, 1.0); }, 1, "parts[0].pos");
  require_bad([&] { set.add_compound({0, 0, 0}, {ball(1, {})}, 0.0); }, 1, "mass");
  require_bad([&] { set.add_compound({0, 0, 0}, std::vector<Part<double>>(max_parts + 1, ball(1, {})), 1.0); }, 1,
              "parts");
  CHECK(set.size() == 1);
  CHECK(set.parts().empty());
  // A record changed in place is checked against its parts at validation.
  set.add_compound({0, 0, 0}, {ball(1, {}), ball(1, {2, 0, 0})}, 1.0);
  set[1].first_part = 1;
  require_bad([&] { set.validate(); }, 1, "first_part");
  set[1].first_part = 0;
  set[1].shape_param[0] = 0;
  require_bad([&] { set.validate(); }, 1, "parts");
}

TEST_CASE("each shape kind's facts come from its traits, and a value that names no kind is refused", "[rbd][bodies]") {
  // Bounds and feature sizes from the parameter slots, against the closed forms.
  CHECK(shape_bound<double>(sphere, 0.7, 0, 0) == 0.7);
  CHECK(shape_bound<double>(box, 1, 2, 2) == Approx(3.0));
  CHECK(shape_bound<double>(capsule, 0.5, 1.5, 0) == 2.0);
  CHECK(std::isinf(shape_bound<double>(plane, 0, 0, 1)));
  CHECK(shape_bound<double>(compound, 3, 2.5, 0.2) == 2.5);  // (parts, bound, feature)
  CHECK(shape_feature_size<double>(box, 1, 0.3, 2) == 0.3);
  CHECK(shape_feature_size<double>(capsule, 0.5, 1.5, 0) == 0.5);
  CHECK(shape_feature_size<double>(compound, 3, 2.5, 0.2) == 0.2);
  CHECK(std::isinf(shape_feature_size<double>(plane, 0, 0, 1)));
  // Names, which kinds a compound may hold, and the kinds as the mask's bits.
  const char* names[shape_kinds] = {"sphere", "box", "plane", "capsule", "compound"};
  for (int k = 0; k < shape_kinds; ++k) CHECK(std::string(shape_name(std::uint8_t(k))) == names[k]);
  CHECK(std::string(shape_name(7)) == "unknown");
  CHECK(part_kinds == (shape_bit(sphere) | shape_bit(box) | shape_bit(capsule)));
  CHECK(primitives == (all_shapes & ~shape_bit(compound)));
  CHECK(!part_kind(7));
  // A record of no kind, and a moving plane, are refused by name.
  BodySet<float> s;
  s.add_sphere({0.f, 0.f, 0.f}, 1.f, 1.f);
  Body<float> b = s[0];
  b.shape = ShapeKind(7);
  require_bad([&] { s.add(b); }, 1, "shape");
  CHECK(solid_primitive<float>(box, {1.f, 1.f, 1.f, 0.f}, 8.f).volume == 8.f);
  CHECK_THROWS_AS(solid_primitive<float>(plane, {0.f, 0.f, 1.f, 0.f}, 1.f), InvalidArgumentError);
}
