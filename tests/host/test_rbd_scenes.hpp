// Small scenes and helpers shared by the rbd solver and physics tests (host and GPU).
#pragma once

#include <algorithm>
#include <cmath>
#include <array>
#include <cstddef>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "gpusolve/rbd/bodies/body_set.hpp"
#include "gpusolve/rbd/world.hpp"

namespace rbd_test {

inline constexpr double g = 9.81;  // |gravity| of the scenes, m/s^2

using namespace gpusolve;
using namespace gpusolve::rbd;

// Calls f(Method{}) for each solver method that takes the contact model (all
// five for ConeFriction; AcceleratedCG takes no other), for checks that every
// method must pass alike.
template <class Model = ConeFriction, class F>
void for_every_method(F&& f) {
  f(AcceleratedJacobi<Gather>{});
  f(Jacobi<Gather>{});
  f(ColouredGaussSeidel{});
  f(Substepping<>{});
  if constexpr (std::is_same_v<Model, ConeFriction>) f(AcceleratedCG{});
}

// Whether f() throws InvalidArgumentError with `what` in its message.
template <class F>
bool refused_naming(F&& f, const std::string& what) {
  try {
    f();
  } catch (const InvalidArgumentError& e) {
    return std::string(e.what()).find(what) != std::string::npos;
  }
  return false;
}

// The unit quaternion (w, x, y, z) of a turn by angle about the unit axis (x, y, z).
inline std::array<double, 4> turn(double angle, double x, double y, double z) {
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), s * x, s * y, s * z};
}

// A ground plane z = 0 and a close-packed pile of layers x (n x n) spheres of
// radius r, each layer resting in the hollows of the one below (dense: up to
// 12 contacts per sphere), slightly jittered so no two rows are identical.
template <class T>
BodySet<T> pile(std::size_t n, std::size_t layers, T r = T(0.5), T gap = T(0)) {
  BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  const T d = 2 * r + gap;
  for (std::size_t l = 0; l < layers; ++l) {
    const T shift = (l % 2) ? d / 2 : T(0);
    const T z = r + l * d * std::sqrt(T(2)) / 2;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const T jitter = T(1e-3) * r * T((i * 7 + j * 3 + l) % 5);
        set.add_sphere({i * d + shift + jitter, j * d + shift, z}, r, T(1));
      }
  }
  return set;
}

// n x n x n spheres of radius r on a cubic lattice of spacing 2.6 r, centred
// on the origin, each moving towards the centre at `speed` times its
// distance: a ball that closes up, so that its contacts (with a margin of
// about r) grow from three per sphere to nearly nine. No plane.
template <class T>
BodySet<T> implosion(std::size_t n, T speed, T r = T(0.5)) {
  BodySet<T> set;
  const T d = T(2.6) * r, mid = T(n - 1) / 2;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k) {
        const T x = (T(i) - mid) * d, y = (T(j) - mid) * d, z = (T(k) - mid) * d;
        const std::size_t b = set.add_sphere({x, y, z}, r, T(1));
        set[b].v = {-speed * x, -speed * y, -speed * z};
      }
  return set;
}

// A clump of three spheres of radius 0.22 in a triangle (Chrono's DEM-Engine
// builds grains so), and a hammer: a capsule handle with a box head.
template <class T>
std::vector<Part<T>> clump() {
  std::vector<Part<T>> parts(3);
  const T at[3][2] = {{T(0.2), T(0)}, {T(-0.1), T(0.17)}, {T(-0.1), T(-0.17)}};
  for (int k = 0; k < 3; ++k) parts[k] = {sphere, {T(0.22), 0, 0, 0}, {at[k][0], at[k][1], T(0)}, {1, 0, 0, 0}};
  return parts;
}
template <class T>
std::vector<Part<T>> hammer() {
  return {{capsule, {T(0.12), T(0.3), 0, 0}, {T(-0.1), T(0), T(0)}, {1, 0, 0, 0}},
          {box, {T(0.1), T(0.25), T(0.15), 0}, {T(0.3), T(0), T(0)}, {T(0.9950042), T(0.0998334), 0, 0}}};
}

// A heap of every moving shape: n x n columns of `layers` bodies on the plane
// z = 0, spaced 1.1 apart (a capsule reaches 0.7, so columns touch), the
// bodies of a row along y of one kind, the rows and layers sphere, box,
// capsule and compound (clump or hammer, in turn along y) in turn, turned a little at random (seed fixed), the layers 0.9
// apart: the heap settles with every shape pair in contact.
template <class T>
BodySet<T> mixed_heap(std::size_t n, std::size_t layers, unsigned seed = 3) {
  BodySet<T> set;
  set.add_plane({0, 0, 1}, 0);
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> tilt(-0.15, 0.15);
  for (std::size_t l = 0; l < layers; ++l)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t k = i + l;
        const std::array<T, 3> x{T(1.1 * double(i)), T(1.1 * double(j)), T(0.45 + 0.9 * double(l))};
        const double a = tilt(gen), b = tilt(gen);
        const double w = std::sqrt(1 - a * a - b * b);
        const std::array<T, 4> q{T(w), T(a), T(b), T(0)};
        if (k % 4 == 0) set.add_sphere(x, T(0.45), T(1));
        if (k % 4 == 1) set.add_box(x, {T(0.45), T(0.52), T(0.35)}, T(1), q);
        if (k % 4 == 2) set.add_capsule(x, T(0.3), T(0.4), T(1), q);
        if (k % 4 == 3) set.add_compound(x, (i + j) % 2 ? clump<T>() : hammer<T>(), T(1), q);
      }
  return set;
}

// Collision detection and the external velocity change of one step, as
// World::step does them before its solve: the input of a solver.
template <class Device, class T, class Model>
void prepare_solve(Bodies<Device, T>& bodies, Contacts<Device, T, Model>& contacts, const SolverSettings<T>& s) {
  CollisionDetection<Device, T> cd;
  cd.detect(bodies, contacts, s.margin, s.friction);
  apply_forces(bodies, s.dt, math::Vector3<T>(s.gravity[0], s.gravity[1], s.gravity[2]));
}

// Velocities (v then w, body-major) of a host store.
template <class T>
std::vector<T> velocities(Bodies<device::cpu, T>& b) {
  std::vector<T> out;
  for (std::size_t k = 0; k < b.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c) out.push_back(b.v(k, c)), out.push_back(b.w(k, c));
  return out;
}

// Impulses (contact-major) of a host store.
template <class T, class Model>
std::vector<T> impulses(Contacts<device::cpu, T, Model>& c) {
  std::vector<T> out;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t r = 0; r < Model::rows; ++r) out.push_back(c.x(i, r));
  return out;
}

template <class T>
T max_abs_diff(const std::vector<T>& a, const std::vector<T>& b) {
  T m = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) m = std::fmax(m, std::fabs(a[i] - b[i]));
  return a.size() == b.size() ? m : T(INFINITY);
}

// The records of `set` in a random order (seed fixed): a heap whose bodies sit
// anywhere in memory, as in a pile that has mixed.
template <class T>
BodySet<T> shuffled(BodySet<T> set, unsigned seed = 11) {
  std::mt19937 gen(seed);
  std::shuffle(set.records().begin(), set.records().end(), gen);
  return set;
}

// World w's positions after a syncHost, body by body (x, y, z) in `set`'s order.
template <class W, class T>
std::vector<T> positions(W& w, BodySet<T>& set) {
  w.syncHost();
  std::vector<T> x;
  for (const auto& b : set.records())
    for (int c = 0; c < 3; ++c) x.push_back(b.pos[c]);
  return x;
}

}  // namespace rbd_test
