// Compound bodies (pe's Union): mass properties by the parallel-axis theorem,
// synchronisation of the parts, frames, and a
// free compound keeping its angular momentum; a clump at rest on a plane.
#include <array>
#include <cmath>
#include <iomanip>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/rbd/io/snapshot.hpp"
#include "test_rbd_scenes.hpp"

using namespace rbd_test;

namespace {

// A sphere part of radius r centred at `at`.
Part<double> ball_at(double r, std::array<double, 3> at) { return {sphere, {r, 0, 0, 0}, at, {1, 0, 0, 0}}; }

// The world-frame angular momentum R I R^T w of body i of a World's host records.
std::array<double, 3> angular_momentum(const Body<double>& b) {
  const auto R = math::to_rotation_matrix(math::Quaternion<double>(b.q[0], b.q[1], b.q[2], b.q[3]));
  const math::Matrix3x3<double> I(b.inertia[0], b.inertia[1], b.inertia[2], b.inertia[3], b.inertia[4],
                                  b.inertia[5], b.inertia[6], b.inertia[7], b.inertia[8]);
  const math::Matrix3x3<double> Iw = math::rotate_tensor(R, I);
  const math::Vector3<double> L(Iw * math::Vector3<double>(b.w[0], b.w[1], b.w[2]));
  return {L[0], L[1], L[2]};
}

}  // namespace

TEST_CASE("a compound's mass properties follow the parallel-axis theorem", "[rbd][compound]") {
  BodySet<double> set;
  // Two spheres of radius 0.5 at x = 1 and 3 of the compound's frame, which
  // lies at x = 5: the centre of mass is at x = 7, the parts at -1 and +1.
  const std::size_t i = set.add_compound({5, 0, 0}, {ball_at(0.5, {1, 0, 0}), ball_at(0.5, {3, 0, 0})}, 2.0);
  const Body<double>& b = set[i];
  CHECK(b.shape == compound);
  CHECK(b.pos[0] == Approx(7.0));
  CHECK(set.parts()[0].pos[0] == Approx(-1.0));
  CHECK(set.parts()[1].pos[0] == Approx(1.0));
  // Each sphere: mass 1, own inertia 2/5 m r^2 = 0.1; about the centre + m d^2 = 1.
  CHECK(b.inertia[0] == Approx(0.2));
  CHECK(b.inertia[4] == Approx(2.2));
  CHECK(b.inertia[8] == Approx(2.2));
  CHECK(b.inv_inertia_body[4] == Approx(1 / 2.2));
  CHECK(b.shape_param[0] == 2);                 // parts
  CHECK(b.shape_param[1] == Approx(1.5));       // bounding radius: 1 + 0.5
  CHECK(b.shape_param[2] == Approx(0.5));       // feature size
  CHECK(b.inv_mass == Approx(0.5));

  // One box turned 90 degrees about z: the box's inertia with x and y swapped.
  const double s = std::sqrt(0.5);
  const std::size_t k =
      set.add_compound({0, 0, 0}, {Part<double>{box, {1.0, 0.5, 0.25, 0}, {0, 0, 0}, {s, 0, 0, s}}}, 3.0);
  const auto own = solid_box<double>({1.0, 0.5, 0.25}, 3.0).inertia;
  CHECK(set[k].inertia[0] == Approx(own[1]));
  CHECK(set[k].inertia[4] == Approx(own[0]));
  CHECK(set[k].inertia[8] == Approx(own[2]));
  CHECK(std::abs(set[k].inertia[1]) < 1e-12);

  // A sphere and a box share the mass by volume; off-centre parts give
  // products of inertia: here the full tensor against the sum by hand.
  const std::vector<Part<double>> mixed = {ball_at(1.0, {0, 0, 0}), Part<double>{box, {0.5, 0.5, 0.5, 0}, {1.5, 1.0, 0}, {1, 0, 0, 0}}};
  const auto c = solid_compound(mixed, 10.0);
  const double vs = 4 * pi / 3, vb = 1.0, ms = 10 * vs / (vs + vb), mb = 10 - ms;
  CHECK(c.volume == Approx(vs + vb));
  CHECK(c.centre[0] == Approx(mb * 1.5 / 10));
  CHECK(c.centre[1] == Approx(mb * 1.0 / 10));
  const double ds[2] = {-c.centre[0], -c.centre[1]}, db[2] = {1.5 - c.centre[0], 1.0 - c.centre[1]};
  const double Is = 0.4 * ms, Ib = mb * 0.5 / 3;  // own inertias about each axis
  CHECK(c.inertia[0] == Approx(Is + Ib + ms * ds[1] * ds[1] + mb * db[1] * db[1]));
  CHECK(c.inertia[1] == Approx(-ms * ds[0] * ds[1] - mb * db[0] * db[1]));
  CHECK(c.inertia[8] == Approx(Is + Ib + ms * (ds[0] * ds[0] + ds[1] * ds[1]) + mb * (db[0] * db[0] + db[1] * db[1])));
  CHECK(c.inertia[3] == Approx(c.inertia[1]));
}

TEST_CASE("the BodyManager copies the parts of compounds added after the first sync", "[rbd][compound]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  set.add_sphere({0, 0, 1}, 0.5, 1);
  BodyManager<device::cpu, double> m(set);
  m.syncDevice();
  CHECK(m.device().shapes == spheres_and_planes);
  const std::size_t i = set.add_compound({3, 0, 1}, hammer<double>(), 1.0, {std::sqrt(0.5), 0, 0, std::sqrt(0.5)});
  m.bodyAdded(i);
  m.syncDevice();
  auto& d = m.device();
  CHECK(d.shapes == (spheres_and_planes | shape_bit(box) | shape_bit(capsule) | shape_bit(compound)));
  REQUIRE(d.parts.size() == 2);
  // Part 1 (the head) placed in the world: the body turned 90 degrees about z.
  std::uint8_t kind = 0;
  const auto head = rbd::detail::placed_primitive<double>(d.view(), i, 1, kind);
  CHECK(kind == box);
  const auto& part = set.parts()[1];
  CHECK(head.x[0] == Approx(set[i].pos[0] - part.pos[1]));
  CHECK(head.x[1] == Approx(set[i].pos[1] + part.pos[0]));
  CHECK(head.x[2] == Approx(set[i].pos[2] + part.pos[2]));
  CHECK(d.radius(i) == Approx(set[i].shape_param[1]));
}

TEST_CASE("the BodyManager removes and compacts compounds of a type, which keep their shared parts", "[rbd][compound]") {
  BodySet<double> set;
  const CompoundType<double> type = set.add_compound_type(clump<double>(), 1.0);
  set.add_plane({0, 0, 1}, 0);
  for (int k = 0; k < 3; ++k) set.add_compound({2.0 * k, 0, 1}, type);
  BodyManager<device::cpu, double> m(set, 1);  // every removal compacts at once
  m.syncDevice();
  m.bodyRemoved(2);
  REQUIRE(m.syncDevice().rebuilt);
  REQUIRE(set.size() == 3);
  CHECK(set[2].pos[0] == Approx(4.0 + type.centre[0]));  // the last clump moved down to index 2
  CHECK(set[2].first_part == type.first_part);
  CHECK(set.parts().size() == 3);  // parts stay with their type
  auto& d = m.device();
  REQUIRE(d.parts.size() == 3);
  std::uint8_t kind = 0;
  const auto first = rbd::detail::placed_primitive<double>(d.view(), 2, 0, kind);
  CHECK(kind == sphere);
  CHECK(first.x[0] == Approx(set[2].pos[0] + set.parts()[0].pos[0]));
  // A compound added after the compaction shares the type's rows too.
  m.bodyAdded(set.add_compound({8, 0, 1}, type));
  m.syncDevice();
  CHECK(d.parts.size() == 3);
  CHECK(d.first_part(3) == type.first_part);
  CHECK(d.radius(3) == Approx(type.bound));
}

TEST_CASE("a compound is drawn as its parts", "[rbd][compound][io]") {
  BodySet<double> set;
  set.add_compound({0, 0, 2}, hammer<double>(), 1.0);
  const io::Frame f = io::snapshot(set, 0, 0.0);
  REQUIRE(f.boxes.size() == 1);
  REQUIRE(f.capsules.size() == 1);
  CHECK(f.boxes[0].moving);
  // Parts at their places in the hammer's frame, which lies at (0, 0, 2).
  CHECK(f.boxes[0].center[0] == Approx(0.3));
  CHECK(f.capsules[0].center[0] == Approx(-0.1));
  CHECK(f.capsules[0].center[2] == Approx(2.0));
  CHECK(f.boxes[0].R[5] == Approx(-std::sin(0.2)).margin(1e-6));  // the head's own turn about x
}

TEST_CASE("a free compound spinning in space keeps its angular momentum", "[rbd][compound][rbd_physics]") {
  BodySet<double> set;
  const std::size_t i = set.add_compound({0, 0, 0}, hammer<double>(), 2.0);
  set[i].w = {1.0, 2.0, 3.0};
  set[i].v = {0.5, 0, 0};
  SolverSettings<double> s;
  s.gravity[2] = 0;
  s.dt = 0.001;
  const double x0 = set[i].pos[0];
  World<device::cpu, double> w(set, s);
  // The rotational kinetic energy w . L / 2.
  const auto energy = [&] {
    const auto L = angular_momentum(set[i]);
    return (set[i].w[0] * L[0] + set[i].w[1] * L[1] + set[i].w[2] * L[2]) / 2;
  };
  const auto L0 = angular_momentum(set[i]);
  const double norm0 = std::sqrt(L0[0] * L0[0] + L0[1] * L0[1] + L0[2] * L0[2]), E0 = energy();
  double worst = 0, most_energy = E0;
  for (int step = 0; step < 2000; ++step) {
    w.step();
    if (step % 100 != 99) continue;
    w.syncHost();
    const auto L = angular_momentum(set[i]);
    const double d = std::sqrt((L[0] - L0[0]) * (L[0] - L0[0]) + (L[1] - L0[1]) * (L[1] - L0[1]) +
                               (L[2] - L0[2]) * (L[2] - L0[2]));
    worst = std::max(worst, d / norm0);
    most_energy = std::max(most_energy, energy());
  }
  INFO(std::setprecision(10) << "largest change of the angular momentum over 2 s: " << worst << " of its size; energy " << E0 << " at the "
                                                            << "start, at most " << most_energy);
  CHECK(worst < 1e-10);  // Move turns L with the body (integrate.hpp)
  CHECK(most_energy - E0 <= 1e-6 * E0);  // no gain (the trapezoidal turn; it was +0.23% with Euler's)
  CHECK(set[i].pos[0] == Approx(x0 + 0.5 * 2.0));  // the centre of mass moves on at v
}

TEST_CASE("a clump resting on a plane has a contact per sphere and stays put", "[rbd][compound][rbd_physics]") {
  BodySet<double> set;
  set.add_plane({0, 0, 1}, 0);
  const std::size_t i = set.add_compound({0, 0, 0.22}, clump<double>(), 1.0);
  const auto start = set[i].pos;
  SolverSettings<double> s;
  s.dt = 0.002, s.margin = 0.02, s.tolerance = 1e-9, s.max_iterations = 400;
  World<device::cpu, double> w(set, s);
  for (int step = 0; step < 500; ++step) REQUIRE(w.step().solver.contacts == 3);
  w.syncHost();
  for (int c = 0; c < 3; ++c) CHECK(std::abs(set[i].pos[c] - start[c]) < 1e-3 * 0.22);
}

TEST_CASE("a compound type is stored once and steps as compounds with parts of their own", "[rbd][compound][rbd_physics]") {
  // Two clump piles from the same places and turns: one of compounds with
  // parts of their own, one of bodies of a single type.
  BodySet<double> own, shared;
  const CompoundType<double> type = shared.add_compound_type(clump<double>(), 1.0);
  for (BodySet<double>* set : {&own, &shared}) set->add_plane({0, 0, 1}, 0);
  for (int k = 0; k < 60; ++k) {
    const std::array<double, 3> at{0.3 * (k % 4), 0.2 * (k % 3), 0.3 + 0.45 * k};
    const auto q = turn(0.7 * k, 0.6, 0, 0.8);
    own.add_compound(at, clump<double>(), 1.0, q);
    shared.add_compound(at, type, q);
  }
  CHECK(own.parts().size() == 60 * clump<double>().size());
  CHECK(shared.parts().size() == clump<double>().size());
  for (std::size_t i = 1; i < own.size(); ++i) {
    CHECK(shared[i].first_part == 0);
    for (int c = 0; c < 3; ++c) CHECK(shared[i].pos[c] == own[i].pos[c]);
    for (int c = 0; c < 9; ++c) CHECK(shared[i].inv_inertia_body[c] == own[i].inv_inertia_body[c]);
    for (int c = 0; c < 4; ++c) CHECK(shared[i].shape_param[c] == own[i].shape_param[c]);
  }
  SolverSettings<double> s;
  s.dt = 0.002;
  World<device::cpu, double> a(own, s), b(shared, s);
  for (int step = 0; step < 300; ++step) REQUIRE(a.step().solver.contacts == b.step().solver.contacts);
  a.syncHost();
  b.syncHost();
  for (std::size_t i = 1; i < own.size(); ++i)
    for (int c = 0; c < 3; ++c) REQUIRE(shared[i].pos[c] == own[i].pos[c]);
}

TEST_CASE("a compound type takes its mass and principal inertia outright for overlapping parts", "[rbd][compound]") {
  BodySet<double> set;
  // Two balls of radius 0.5 whose centres lie 0.6 apart overlap: summing
  // their volumes would count the lens twice, so the user gives the figures.
  const std::vector<Part<double>> peanut = {ball_at(0.5, {-0.3, 0, 0}), ball_at(0.5, {0.3, 0, 0})};
  const CompoundType<double> t = set.add_compound_type(peanut, 2.0, {0.15, 0.3, 0.3});
  CHECK(t.count == 2);
  CHECK(t.bound == Approx(0.8));
  CHECK(set.parts()[0].pos[0] == -0.3);  // placed as given: the frame is the centre of mass
  const std::size_t i = set.add_compound({1, 2, 3}, t);
  CHECK(set[i].pos == std::array<double, 3>{1, 2, 3});
  CHECK(set[i].inv_mass == 0.5);
  CHECK(set[i].inertia[0] == 0.15);
  CHECK(set[i].inv_inertia_body[4] == Approx(1 / 0.3));
  CHECK(set[i].inertia[1] == 0);
  // Bad figures name the field; a refused type stores no parts.
  const auto field_of = [](auto&& add) {
    try {
      add();
    } catch (const InvalidBodyError& e) {
      return e.field();
    }
    return std::string("none");
  };
  CHECK(field_of([&] { set.add_compound_type(peanut, 2.0, {0.15, 0, 0.3}); }) == "inertia");
  CHECK(field_of([&] { set.add_compound_type(peanut, -1.0); }) == "mass");
  CHECK(field_of([&] { set.add_compound_type({ball_at(0.5, {0, 0, 0}), ball_at(-1, {1, 0, 0})}, 1.0); }) ==
        "parts[1].radius");
  CHECK(field_of([&] { set.add_compound({0, 0, 0}, t, {1, 1, 0, 0}); }) == "q");
  CHECK(field_of([&] { set.add_compound({0, 0, 0}, clump<double>(), 1.0, {2, 0, 0, 0}); }) == "q");
  CHECK(set.parts().size() == 2);
  CHECK(set.size() == 1);
}

namespace {

// A manifold of normal +z whose points lie at (x, y, gap) in the plane z = 0.
Manifold<double> flat(std::initializer_list<std::array<double, 3>> pts, std::uint32_t part) {
  Manifold<double> m;
  m.n = math::Vector3<double>(0, 0, 1);
  std::uint32_t f = 0;
  for (const auto& p : pts) m.add(math::Vector3<double>(p[0], p[1], 0), p[2], part_feature(f++, part, 0));
  return m;
}

// The points the merged sets hand out, as (x, y, gap).
std::vector<std::array<double, 3>> merged_points(MergedManifolds<double>& mm) {
  std::vector<std::array<double, 3>> out;
  mm.for_each([&](const Manifold<double>& m) {
    for (int k = 0; k < m.count; ++k) out.push_back({m.points[k].p[0], m.points[k].p[1], m.points[k].gap});
  });
  return out;
}

}  // namespace

TEST_CASE("merged manifolds keep the corners of the region their points span, and the deepest point", "[rbd][compound][collision]") {
  SECTION("four tiles of a face, merged in any order, keep the face's four corners") {
    MergedManifolds<double> mm;
    int part = 0;
    for (double x : {-0.5, 0.5})
      for (double y : {-0.5, 0.5})
        CHECK(mm.merge(flat({{x - 0.5, y - 0.5, 0}, {x + 0.5, y - 0.5, 0}, {x - 0.5, y + 0.5, 0}, {x + 0.5, y + 0.5, 0}},
                            std::uint32_t(part++))));
    const auto pts = merged_points(mm);
    REQUIRE(pts.size() == 4);
    for (const auto& p : pts) CHECK((std::fabs(p[0]) == 1.0 && std::fabs(p[1]) == 1.0));
  }
  SECTION("a handle and a head meeting the floor keep every corner of the region they span") {
    // The handle's two points on its axis, the head's four corners beside it:
    // five corners (the handle's inner point lies within them), more than four.
    MergedManifolds<double> mm;
    mm.merge(flat({{-1.5, 0, 0.02}, {0.5, 0, 0.0}}, 0));
    mm.merge(flat({{0.8, -0.7, -0.001}, {1.6, -0.7, 0.03}, {0.8, 0.7, 0.0}, {1.6, 0.7, 0.05}}, 1));
    const auto pts = merged_points(mm);
    CHECK(pts.size() == 5);
    const auto has = [&](double x, double y) {
      for (const auto& p : pts)
        if (p[0] == x && p[1] == y) return true;
      return false;
    };
    CHECK(has(-1.5, 0));
    CHECK(has(0.8, -0.7));  // the deepest
    CHECK(has(1.6, -0.7));
    CHECK(has(0.8, 0.7));
    CHECK(has(1.6, 0.7));
  }
  SECTION("an inner point deeper than every corner is kept") {
    MergedManifolds<double> mm;
    mm.merge(flat({{-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}}, 0));
    mm.merge(flat({{0, 0, -0.05}}, 1));
    CHECK(merged_points(mm).size() == 5);
  }
  SECTION("normals apart by more than 3 degrees stay apart") {
    MergedManifolds<double> mm;
    mm.merge(flat({{0, 0, 0}}, 0));
    Manifold<double> side = flat({{1, 0, 0}}, 1);
    side.n = math::Vector3<double>(std::sin(0.1), 0, std::cos(0.1));  // 5.7 degrees
    mm.merge(side);
    CHECK(mm.sets == 2);
  }
}
