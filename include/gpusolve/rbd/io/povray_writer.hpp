// POV-Ray scene writer of a frame: spheres, boxes, capsules, planes, a camera and lights (thesis Fig. 16).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/io/frame.hpp"

namespace gpusolve::rbd::io {

// Camera and lights, in simulation coordinates (z up). With auto_camera the
// camera looks at the centre of the spheres' and boxes' bounding box from the
// direction `view_dir`, far enough to see all of it.
struct PovOptions {
  bool auto_camera = true;
  Frame::Vec3 camera{0, -30, 20};
  Frame::Vec3 look_at{0, 0, 0};
  Frame::Vec3 view_dir{0.8, -1.6, 1.0};
  double angle_deg = 40.0;  // horizontal field of view
  double aspect = 4.0 / 3.0;
};

namespace detail {

// POV-Ray is left-handed with y up: swapping y and z maps our right-handed z-up
// coordinates onto it (the swap is also the handedness flip).
inline std::string pov_vec(const Frame::Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "<%.6g, %.6g, %.6g>", v[0], v[2], v[1]);
  return buf;
}

inline void pov_camera(const Frame& f, PovOptions& o) {
  if (!o.auto_camera) return;
  constexpr double inf = std::numeric_limits<double>::infinity();
  Frame::Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  auto grow = [&](const Frame::Vec3& p, double r) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k] - r), hi[k] = std::max(hi[k], p[k] + r);
  };
  for (std::size_t i = 0; i < f.spheres.size(); ++i) grow(f.spheres.pos[i], f.spheres.radius[i]);
  for (const auto& b : f.boxes)
    for (const auto& c : box_corners(b)) grow(c, 0.0);
  for (const auto& c : f.capsules)
    for (const auto& e : Frame::ends(c)) grow(e, c.radius);
  if (lo[0] > hi[0]) lo = {-1, -1, -1}, hi = {1, 1, 1};  // nothing finite to frame
  double r2 = 0;
  for (int k = 0; k < 3; ++k) {
    o.look_at[k] = 0.5 * (lo[k] + hi[k]);
    r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
  }
  const auto& d = o.view_dir;
  const double ld = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  // Vertical field of view is the tighter one for a landscape picture.
  const double half = std::atan(std::tan(o.angle_deg * (3.14159265358979323846 / 360.0)) / std::max(o.aspect, 1.0));
  const double dist = 1.05 * std::sqrt(r2) / std::sin(half);
  for (int k = 0; k < 3; ++k) o.camera[k] = o.look_at[k] + dist * d[k] / ld;
}

}  // namespace detail

// Writes a self-contained .pov file. Spheres, moving boxes and capsules cycle
// through six colours by index, fixed boxes are walls;
// a plane is drawn only when the camera is on its open side (a closed box would
// otherwise hide everything inside).
inline void write_povray(const std::string& path, const Frame& f, PovOptions o = {}) {
  std::ofstream out(path);
  if (!out) throw InvalidArgumentError("write_povray: cannot open '" + path + "' for writing");
  detail::pov_camera(f, o);
  using detail::pov_vec;
  const Frame::Vec3 light{o.camera[0] - 0.5 * (o.camera[1] - o.look_at[1]), o.camera[1],
                          o.camera[2] + 2.0 * std::fabs(o.camera[2] - o.look_at[2]) + 10.0};
  out << "// gpusolve frame: step " << f.step << ", time " << f.time << ", " << f.spheres.size()
      << " spheres\n#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\n"
      << "background { color rgb <1, 1, 1> }\n"
      << "camera { location " << pov_vec(o.camera) << " look_at " << pov_vec(o.look_at)
      << " right x*" << o.aspect << " angle " << o.angle_deg << " }\n"
      << "light_source { " << pov_vec(light) << " color rgb 1 }\n"
      << "light_source { " << pov_vec(o.camera) << " color rgb 0.35 shadowless }\n";
  static constexpr const char* palette[6] = {"0.80, 0.15, 0.12", "0.95, 0.65, 0.10", "0.20, 0.55, 0.85",
                                             "0.25, 0.70, 0.30", "0.60, 0.30, 0.75", "0.90, 0.90, 0.85"};
  for (int k = 0; k < 6; ++k)
    out << "#declare S" << k << " = texture { pigment { color rgb <" << palette[k]
        << "> } finish { phong 0.6 diffuse 0.8 } }\n";
  out << "#declare Wall = texture { pigment { color rgb <0.62, 0.58, 0.52> } finish { diffuse 0.9 } }\n"
      << "#declare Floor = texture { pigment { checker color rgb 0.85 color rgb 0.7 scale 4 } }\n";

  const auto& s = f.spheres;
  for (std::size_t i = 0; i < s.size(); ++i)
    out << "sphere { " << pov_vec(s.pos[i]) << ", " << s.radius[i] << " texture { S" << i % 6 << " } }\n";
  for (std::size_t i = 0; i < f.boxes.size(); ++i) {
    // POV-Ray applies `matrix` to row vectors: its rows are the columns of S*R
    // (S swaps y and z), then the translation.
    const auto& b = f.boxes[i];
    const auto& R = b.R;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "box { <%.6g, %.6g, %.6g>, <%.6g, %.6g, %.6g> matrix <%.6g, %.6g, %.6g, %.6g, %.6g, "
                  "%.6g, %.6g, %.6g, %.6g, %.6g, %.6g, %.6g> texture { ",
                  -b.half[0], -b.half[1], -b.half[2], b.half[0], b.half[1], b.half[2], R[0], R[6], R[3],
                  R[1], R[7], R[4], R[2], R[8], R[5], b.center[0], b.center[2], b.center[1]);
    out << buf << (b.moving ? "S" + std::to_string(i % 6) : std::string("Wall")) << " } }\n";
  }
  for (std::size_t i = 0; i < f.capsules.size(); ++i) {  // a sphere swept along the core segment
    const auto& c = f.capsules[i];
    const auto e = Frame::ends(c);
    out << "sphere_sweep { linear_spline 2, " << pov_vec(e[0]) << ", " << c.radius << ", " << pov_vec(e[1]) << ", "
        << c.radius << " texture { S" << (i + 3) % 6 << " } }\n";
  }
  for (const auto& p : f.planes) {
    const auto& n = p.normal;
    if (n[0] * o.camera[0] + n[1] * o.camera[1] + n[2] * o.camera[2] < p.d) continue;
    out << "plane { " << pov_vec(n) << ", " << p.d << " texture { Floor } }\n";
  }
}

}  // namespace gpusolve::rbd::io
