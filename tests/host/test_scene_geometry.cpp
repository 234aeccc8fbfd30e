// Tests of the scenes program's option parser and of the three scenes' geometry.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../../examples/scene_ballpark.hpp"
#include "../../examples/scene_hopper.hpp"
#include "../../examples/scene_options.hpp"
#include "../../examples/scene_well.hpp"
#include "catch_compat.hpp"
#include "gpusolve/rbd/io/snapshot.hpp"

using gpusolve::rbd::BodySet;
using gpusolve::rbd::io::Frame;

namespace {

scenes::Options parse(std::vector<const char*> args) {
  args.insert(args.begin(), "gpusolve_scenes");
  return scenes::parse_options(static_cast<int>(args.size()), args.data(), {"cache", "atomic"});
}

template <class Scene>
scenes::Options resolved(const char* scene, long steps, long scale) {
  const std::string s = std::to_string(steps), n = std::to_string(scale);
  auto o = parse({scene, "--steps", s.c_str(), "--scale", n.c_str(), "--seed", "7"});
  o.resolve(Scene::defaults());
  return o;
}

// Distance from p to the solid box b (0 inside).
double box_distance(const Frame::Box& b, const Frame::Vec3& p) {
  double d2 = 0;
  for (int c = 0; c < 3; ++c) {
    double local = 0;  // component c of R^T (p - centre)
    for (int r = 0; r < 3; ++r) local += b.R[3 * r + c] * (p[r] - b.center[r]);
    const double out = std::fabs(local) - b.half[c];
    if (out > 0) d2 += out * out;
  }
  return std::sqrt(d2);
}

double min_box_distance(const Frame& f, const Frame::Vec3& p) {
  double d = INFINITY;
  for (const auto& b : f.boxes) d = std::min(d, box_distance(b, p));
  return d;
}

// Smallest distance between two sphere centres (brute force).
double closest_pair(const Frame& f) {
  double best = INFINITY;
  const auto& p = f.spheres.pos;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      best = std::min(best, std::hypot(p[i][0] - p[j][0], p[i][1] - p[j][1], p[i][2] - p[j][2]));
  return best;
}

}  // namespace

TEST_CASE("the option parser reads every option and resolves scene defaults", "[scene]") {
  auto o = parse({"well", "--backend=cpu", "--steps", "300", "--dt", "0.001", "--omega", "0.7",
                  "--accumulation", "atomic", "--friction", "0", "--out", "/tmp/x", "--frame-every", "10",
                  "--frames", "vtk", "--quiet"});
  CHECK(o.scene == "well");
  CHECK(o.backend == "cpu");
  CHECK(*o.steps == 300);
  CHECK(*o.dt == Approx(0.001));
  CHECK(o.omega == Approx(0.7));
  CHECK(o.accumulation == "atomic");
  CHECK(*o.friction == 0.0);
  CHECK(o.wants("vtk"));
  CHECK_FALSE(o.wants("pov"));
  CHECK(o.quiet);
  CHECK_FALSE(o.scale.has_value());
  o.resolve(scenes::Well<float>::defaults());
  CHECK(*o.scale == 3900);
  CHECK(*o.tolerance == Approx(5e-3));
  CHECK(*o.max_iterations == 2000);
  CHECK(*o.check_every == 50);
  CHECK(*o.steps == 300);  // the command line wins over the scene
  CHECK(o.out == "/tmp/x");

  auto h = parse({"--scene", "hopper"});
  h.resolve(scenes::Hopper<float>::defaults());
  CHECK(h.out == "out/hopper");
  CHECK(*h.scale == 9857);
}

TEST_CASE("the option parser rejects bad command lines with a message", "[scene]") {
  using scenes::UsageError;
  CHECK_THROWS_AS(parse({}), UsageError);
  CHECK_THROWS_AS(parse({"volcano"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--steps", "ten"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--steps", "0"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--dt", "-1"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--dt", "nan"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--omega", "2"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--warm-start", "1.5"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--warm-start", "-0.1"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--backend", "tpu"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--accumulation", "magic"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--frames", "vtk,png"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--bogus"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--quiet=yes"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "--steps"}), UsageError);
  CHECK_THROWS_AS(parse({"well", "hopper"}), UsageError);
  try {
    parse({"well", "--tolerance", "abc"});
  } catch (const UsageError& e) {
    CHECK(std::string(e.what()).find("--tolerance") != std::string::npos);
    CHECK(std::string(e.what()).find("abc") != std::string::npos);
  }
  CHECK(parse({"--help"}).help);
}

TEST_CASE("ballpark: a misaligned block of separate spheres inside six walls", "[scene]") {
  const auto o = resolved<scenes::Ballpark<double>>("ballpark", 10, 343);
  scenes::Ballpark<double> scene(o);
  BodySet<double> set;
  scene.build(set);
  const Frame f = gpusolve::rbd::io::snapshot(set, 0, 0.0);
  REQUIRE(f.planes.size() == 6);
  REQUIRE(f.spheres.size() == 343);
  CHECK(f.boxes.empty());
  const double gap = closest_pair(f);
  CHECK(gap > 2.0);   // nothing touches at the start
  CHECK(gap < 2.5);   // but the lattice is misaligned
  for (const auto& p : f.spheres.pos)
    for (const auto& pl : f.planes)
      CHECK(pl.normal[0] * p[0] + pl.normal[1] * p[1] + pl.normal[2] * p[2] - pl.d > 1.0);
  // A scale that is not a cube fills a 4x4x4 block in part.
  const auto o2 = resolved<scenes::Ballpark<double>>("ballpark", 10, 50);
  BodySet<double> set2;
  scenes::Ballpark<double>(o2).build(set2);
  CHECK(set2.size() == 6 + 50);
}

TEST_CASE("well: 150 boxes in five rings and a schedule of non-overlapping insertions", "[scene]") {
  const auto o = resolved<scenes::Well<float>>("well", 200, 120);
  scenes::Well<float> scene(o);
  BodySet<float> set;
  scene.build(set);
  Frame f = gpusolve::rbd::io::snapshot(set, 0, 0.0);
  REQUIRE(f.planes.size() == 1);
  REQUIRE(f.boxes.size() == 150);
  CHECK(f.spheres.size() == 0);
  for (const auto& b : f.boxes) {
    CHECK(std::hypot(b.center[0], b.center[1]) == Approx(12.0).epsilon(1e-5));
    CHECK(b.center[2] > 0.0);
    CHECK(b.center[2] < 10.0);
  }
  // The shaft is open: a point on the axis is far from every box, one on the ring is inside one.
  CHECK(min_box_distance(f, {0, 0, 5}) > 10.0);
  CHECK(min_box_distance(f, {12, 0, 1}) == 0.0);

  CHECK(scene.insertion_stop() == 180);
  long previous = 0;
  for (long step = 0; step < 200; ++step) {
    const long want = scene.target(step);
    CHECK(want >= previous);
    previous = want;
    if (!scene.wants_edit(step)) continue;
    const auto c = scene.edit(step, set);
    CHECK(c.removed.empty());
    CHECK(scene.inserted() == want);  // the band is empty enough here: nothing is deferred
  }
  CHECK(scene.inserted() == 120);
  CHECK(scene.target(179) == 120);
  f = gpusolve::rbd::io::snapshot(set, 200, 0.5);
  REQUIRE(f.spheres.size() == 120);
  CHECK(closest_pair(f) >= 2.0);
  for (const auto& p : f.spheres.pos) {
    CHECK(std::hypot(p[0], p[1]) <= 8.0 + 1e-4);
    CHECK(p[2] >= 30.0);
    CHECK(p[2] <= 40.0);
  }
}

TEST_CASE("hopper: a closed funnel above the floor, filled without contacts, lid removed after warm-up", "[scene]") {
  const auto o = resolved<scenes::Hopper<double>>("hopper", 400, 700);
  scenes::Hopper<double> scene(o);
  BodySet<double> set;
  scene.build(set);
  const Frame f = gpusolve::rbd::io::snapshot(set, 0, 0.0);
  REQUIRE(f.planes.size() == 1);
  REQUIRE(f.boxes.size() == 9);
  REQUIRE(f.spheres.size() == 700);
  CHECK(closest_pair(f) > 2.0);
  for (const auto& p : f.spheres.pos) {
    CHECK(std::fabs(p[0]) < 19.0);
    CHECK(std::fabs(p[1]) < 19.0);
    CHECK(min_box_distance(f, p) > 1.0);
  }
  // The funnel's inner faces run at 45 degrees from the outlet edge (4, z = 20).
  for (double h : {2.0, 8.0, 14.0}) {
    CHECK(min_box_distance(f, {4 + h + 0.05, 0, 20 + h}) == 0.0);
    CHECK(min_box_distance(f, {0, -(4 + h + 0.05), 20 + h}) == 0.0);
    CHECK(min_box_distance(f, {4 + h - 0.05, 0, 20 + h}) > 0.0);
  }
  // A sphere resting in the outlet touches the lid only.
  CHECK(min_box_distance(f, {0, 0, 21}) == Approx(1.0));

  CHECK(scene.warmup() == 200);
  CHECK_FALSE(scene.wants_edit(199));
  REQUIRE(scene.wants_edit(200));
  const auto c = scene.edit(200, set);
  REQUIRE(c.removed.size() == 1);
  const auto& lid = set[c.removed[0]];
  CHECK(lid.shape == gpusolve::rbd::box);
  CHECK(lid.pos[2] == Approx(19.5));
}
