// SolverSettings as four groups by concern, and the README's World example on the CPU backend.
#include <string>

#include "catch_compat.hpp"
#include "gpusolve/rbd/world.hpp"

using namespace gpusolve;
using namespace gpusolve::rbd;

namespace {
template <class Group>
std::string message_of(const Group& g) {
  try {
    g.validate();
  } catch (const InvalidArgumentError& e) {
    return e.what();
  }
  return "valid";
}
}  // namespace

TEST_CASE("settings brace-initialise group by group and keep their defaults", "[rbd_settings]") {
  const SolverSettings<float> s{{0.001f, {0, 0, -1.62f}}, {0.05f}, {0.4f}, {}};
  CHECK(s.dt == 0.001f);
  CHECK(s.gravity[2] == -1.62f);
  CHECK(s.margin == 0.05f);
  CHECK(s.correction == 0.2f);  // the rest of a group keeps its defaults
  CHECK(s.omega == 0.4f);
  CHECK(s.max_iterations == 50);
  CHECK(s.persistent_max_contacts == 1000000);
  CHECK_NOTHROW(s.validate());
  // A stage that needs one concern takes its group: the same values.
  const ContactSettings<float>& c = s.contacts();
  CHECK(c.margin == 0.05f);
  CHECK(s.step().dt == 0.001f);
  CHECK(s.solve().omega == 0.4f);
  CHECK_FALSE(s.execution().graphs);
}

TEST_CASE("each settings group validates its own fields and names them", "[rbd_settings]") {
  StepSettings<double> step;
  step.dt = 0;
  CHECK(message_of(step).find("`dt`") != std::string::npos);
  ContactSettings<double> contacts;
  contacts.correction = 1.5;
  CHECK(message_of(contacts).find("`correction`") != std::string::npos);
  SolveSettings<double> solve;
  solve.warm_start = 2;
  CHECK(message_of(solve).find("`warm_start`") != std::string::npos);
  CHECK(message_of(ExecutionSettings{}) == "valid");
  SolverSettings<double> all;
  all.friction = -1;
  CHECK(message_of(all).find("`friction`") != std::string::npos);
}

TEST_CASE("the README's World example runs on the CPU backend", "[rbd_settings]") {
  BodySet<float> set;
  set.add_plane({0, 0, 1}, 0);
  for (int i = 0; i < 32; ++i)  // the README's lattice, two layers of 4 x 4
    set.add_sphere({2.1f * (i % 4), 2.1f * (i / 4 % 4), 1.1f + 2.1f * (i / 16)}, 1.0f, 1.0f);
  SolverSettings<float> settings;
  settings.friction = 0.5f;
  SphereWorld<device::cpu> world(set, settings);
  for (int k = 0; k < 400; ++k) world.advance();  // 1 s: both layers have landed
  const StepStats<float> s = world.latest_stats();
  CHECK(s.solver.contacts >= 32);  // every sphere rests on the floor or on another
  CHECK(s.max_penetration < 0.01f);
  world.syncHost();
  for (std::size_t i = 1; i < set.size(); ++i) CHECK(set[i].pos[2] > 0.98f);
}

TEST_CASE("a SphereWorld steps spheres as World does and refuses a box by name", "[rbd_settings]") {
  BodySet<float> set;
  set.add_plane({0, 0, 1}, 0);
  for (int i = 0; i < 32; ++i)
    set.add_sphere({2.1f * (i % 4) + 0.01f * i, 2.1f * (i / 4 % 4), 1.1f + 2.1f * (i / 16)}, 1.0f, 1.0f);
  BodySet<float> copy = set;
  SolverSettings<float> settings;
  settings.friction = 0.5f;
  World<device::cpu> all(set, settings);
  SphereWorld<device::cpu> spheres(copy, settings);
  all.advance(300);
  spheres.advance(300);
  CHECK(all.latest_stats().solver.contacts == spheres.latest_stats().solver.contacts);
  all.syncHost();
  spheres.syncHost();
  for (std::size_t i = 0; i < set.size(); ++i)
    for (int c = 0; c < 3; ++c) CHECK(set[i].pos[c] == copy[i].pos[c]);  // the same kernels: bit for bit

  copy.add_box({0, 0, 9}, {0.5f, 0.5f, 0.5f}, 1.0f);
  const std::size_t box = copy.size() - 1;
  spheres.manager().bodyAdded(box);
  try {
    spheres.manager().syncDevice();
    FAIL("a box was accepted by a SphereWorld");
  } catch (const InvalidBodyError& e) {
    CHECK(e.body() == box);
    CHECK(e.field() == "shape");
    CHECK(std::string(e.what()).find("not compiled for box") != std::string::npos);
  }
  BodySet<float> boxes;
  boxes.add_box({0, 0, 1}, {0.5f, 0.5f, 0.5f}, 1.0f);
  CHECK_THROWS_AS(SphereWorld<device::cpu>(boxes, settings), InvalidBodyError);
}
