// Frame: a host-side snapshot of a scene's geometry, the input of every frame writer.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace gpusolve::rbd::io {

// Plain arrays of doubles so the writers need neither the containers nor the
// solver: a frame is taken from the bodies once, then written in any format.
// Coordinates are those of the simulation (z up, right-handed).
struct Frame {
  using Vec3 = std::array<double, 3>;

  struct Spheres {
    std::vector<Vec3> pos;
    std::vector<Vec3> vel;
    std::vector<double> radius;
    std::size_t size() const { return radius.size(); }
  };
  struct Box {
    Vec3 center;
    Vec3 half;                     // half extents in the box frame
    std::array<double, 9> R;       // rotation, row-major: world = R * local
    bool moving = false;           // drawn with the moving bodies, not the fixed geometry
  };
  struct Capsule {
    Vec3 center;
    Vec3 axis;                     // unit, world frame: the core segment is center +- half_length * axis
    double radius, half_length;
  };
  struct Plane {
    Vec3 normal;                   // unit, points out of the solid half-space
    double d;                      // points x with normal.x = d lie on the plane
  };

  std::size_t step = 0;
  double time = 0.0;
  Spheres spheres;
  std::vector<Box> boxes;
  std::vector<Plane> planes;
  std::vector<Capsule> capsules;

  // The ends of a capsule's core segment.
  static std::array<Vec3, 2> ends(const Capsule& c) {
    std::array<Vec3, 2> e{};
    for (int r = 0; r < 3; ++r) {
      e[0][r] = c.center[r] - c.half_length * c.axis[r];
      e[1][r] = c.center[r] + c.half_length * c.axis[r];
    }
    return e;
  }

  void add_sphere(const Vec3& p, double r, const Vec3& v = {0.0, 0.0, 0.0}) {
    spheres.pos.push_back(p);
    spheres.radius.push_back(r);
    spheres.vel.push_back(v);
  }
};

// The eight corners of a box in VTK hexahedron order (bottom face, then top face,
// both counter-clockwise seen from +z of the box frame).
inline std::array<Frame::Vec3, 8> box_corners(const Frame::Box& b) {
  static constexpr int sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                     {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  std::array<Frame::Vec3, 8> c{};
  for (int k = 0; k < 8; ++k) {
    const double l[3] = {sign[k][0] * b.half[0], sign[k][1] * b.half[1], sign[k][2] * b.half[2]};
    for (int r = 0; r < 3; ++r)
      c[k][r] = b.center[r] + b.R[3 * r] * l[0] + b.R[3 * r + 1] * l[1] + b.R[3 * r + 2] * l[2];
  }
  return c;
}

}  // namespace gpusolve::rbd::io
