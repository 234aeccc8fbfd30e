// VTK legacy writers of a frame for ParaView: spheres as points with data,
// moving boxes and capsules as cells, fixed geometry as cells.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "gpusolve/core/error.hpp"
#include "gpusolve/rbd/io/frame.hpp"

namespace gpusolve::rbd::io {
namespace detail {

inline std::ofstream open_vtk(const std::string& path, const char* title, const char* dataset) {
  std::ofstream out(path);
  if (!out) throw InvalidArgumentError("vtk: cannot open '" + path + "' for writing");
  out << "# vtk DataFile Version 3.0\n" << title << "\nASCII\nDATASET " << dataset << '\n';
  return out;
}

inline void vtk_vec(std::ofstream& out, const Frame::Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.7g %.7g %.7g\n", v[0], v[1], v[2]);
  out << buf;
}

// ParaView reads the TIME field of a legacy file as the frame's time stamp.
inline void vtk_time(std::ofstream& out, const Frame& f) {
  out << "FIELD FieldData 2\nTIME 1 1 double\n" << f.time << "\nCYCLE 1 1 int\n" << f.step << '\n';
}

}  // namespace detail

// The spheres as a POLYDATA of vertices with point data `radius`, `velocity` and
// `speed`. In ParaView: Glyph, type Sphere, scale by `radius` with factor 2.
inline void write_vtk_spheres(const std::string& path, const Frame& f) {
  const auto& s = f.spheres;
  const std::size_t n = s.size();
  if (s.pos.size() != n || s.vel.size() != n)
    throw SizeMismatchError("write_vtk_spheres: pos, vel and radius differ in length");
  auto out = detail::open_vtk(path, "gpusolve spheres", "POLYDATA");
  detail::vtk_time(out, f);
  out << "POINTS " << n << " float\n";
  for (const auto& p : s.pos) detail::vtk_vec(out, p);
  out << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';
  out << "POINT_DATA " << n << "\nSCALARS radius float 1\nLOOKUP_TABLE default\n";
  for (double r : s.radius) out << r << '\n';
  out << "VECTORS velocity float\n";
  for (const auto& v : s.vel) detail::vtk_vec(out, v);
  out << "SCALARS speed float 1\nLOOKUP_TABLE default\n";
  for (const auto& v : s.vel) out << std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) << '\n';
}

// The moving boxes as hexahedra and the capsules as line cells (their core
// segments) in one UNSTRUCTURED_GRID, with cell data `kind` (0 box, 1 capsule)
// and `radius` (capsules; 0 for boxes). In ParaView: Extract Cells By Type for
// the lines, then Tube, radius from `radius` (Vary Radius: By Absolute Scalar).
inline void write_vtk_shapes(const std::string& path, const Frame& f) {
  std::vector<const Frame::Box*> boxes;
  for (const auto& b : f.boxes)
    if (b.moving) boxes.push_back(&b);
  const std::size_t nb = boxes.size(), nc = f.capsules.size();
  auto out = detail::open_vtk(path, "gpusolve moving shapes", "UNSTRUCTURED_GRID");
  detail::vtk_time(out, f);
  out << "POINTS " << 8 * nb + 2 * nc << " float\n";
  for (const Frame::Box* b : boxes)
    for (const auto& c : box_corners(*b)) detail::vtk_vec(out, c);
  for (const auto& c : f.capsules)
    for (const auto& e : Frame::ends(c)) detail::vtk_vec(out, e);
  out << "CELLS " << nb + nc << ' ' << 9 * nb + 3 * nc << '\n';
  for (std::size_t b = 0; b < nb; ++b) {
    out << 8;
    for (std::size_t k = 0; k < 8; ++k) out << ' ' << 8 * b + k;
    out << '\n';
  }
  for (std::size_t c = 0; c < nc; ++c) out << "2 " << 8 * nb + 2 * c << ' ' << 8 * nb + 2 * c + 1 << '\n';
  out << "CELL_TYPES " << nb + nc << '\n';  // 12: VTK_HEXAHEDRON, 3: VTK_LINE
  for (std::size_t b = 0; b < nb; ++b) out << "12\n";
  for (std::size_t c = 0; c < nc; ++c) out << "3\n";
  out << "CELL_DATA " << nb + nc << "\nSCALARS kind int 1\nLOOKUP_TABLE default\n";
  for (std::size_t b = 0; b < nb; ++b) out << "0\n";
  for (std::size_t c = 0; c < nc; ++c) out << "1\n";
  out << "SCALARS radius float 1\nLOOKUP_TABLE default\n";
  for (std::size_t b = 0; b < nb; ++b) out << "0\n";
  for (const auto& c : f.capsules) out << c.radius << '\n';
}

// The fixed boxes as hexahedra and planes as squares of side 2 * plane_half_extent centred
// at the plane point closest to the origin, in one UNSTRUCTURED_GRID; cell data
// `kind` is 0 for a box, 1 for a plane.
inline void write_vtk_fixed(const std::string& path, const Frame& f, double plane_half_extent) {
  std::vector<const Frame::Box*> boxes;
  for (const auto& b : f.boxes)
    if (!b.moving) boxes.push_back(&b);
  const std::size_t nb = boxes.size(), np = f.planes.size();
  auto out = detail::open_vtk(path, "gpusolve fixed geometry", "UNSTRUCTURED_GRID");
  detail::vtk_time(out, f);
  out << "POINTS " << 8 * nb + 4 * np << " float\n";
  for (const Frame::Box* b : boxes)
    for (const auto& c : box_corners(*b)) detail::vtk_vec(out, c);
  for (const auto& p : f.planes) {
    // Two unit tangents u, w spanning the plane.
    const auto& n = p.normal;
    const Frame::Vec3 a = std::fabs(n[0]) < 0.9 ? Frame::Vec3{1, 0, 0} : Frame::Vec3{0, 1, 0};
    Frame::Vec3 u{a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double& x : u) x /= lu;
    const Frame::Vec3 w{n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    static constexpr int corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corner) {
      Frame::Vec3 q{};
      for (int r = 0; r < 3; ++r)
        q[r] = n[r] * p.d + plane_half_extent * (c[0] * u[r] + c[1] * w[r]);
      detail::vtk_vec(out, q);
    }
  }
  out << "CELLS " << nb + np << ' ' << 9 * nb + 5 * np << '\n';
  for (std::size_t b = 0; b < nb; ++b) {
    out << 8;
    for (std::size_t k = 0; k < 8; ++k) out << ' ' << 8 * b + k;
    out << '\n';
  }
  for (std::size_t p = 0; p < np; ++p) {
    out << 4;
    for (std::size_t k = 0; k < 4; ++k) out << ' ' << 8 * nb + 4 * p + k;
    out << '\n';
  }
  out << "CELL_TYPES " << nb + np << '\n';  // 12: VTK_HEXAHEDRON, 9: VTK_QUAD
  for (std::size_t b = 0; b < nb; ++b) out << "12\n";
  for (std::size_t p = 0; p < np; ++p) out << "9\n";
  out << "CELL_DATA " << nb + np << "\nSCALARS kind int 1\nLOOKUP_TABLE default\n";
  for (std::size_t b = 0; b < nb; ++b) out << "0\n";
  for (std::size_t p = 0; p < np; ++p) out << "1\n";
}

}  // namespace gpusolve::rbd::io
