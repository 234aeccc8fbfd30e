// Narrow phase: the contact geometry of sphere-sphere, sphere-plane and
// sphere-box pairs (thesis Fig. 5): normal, offsets to the contact point, gap.
#pragma once

#include <cmath>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd {

// The geometry of one contact between body a (a sphere) and body b. n points
// from b to a; ra and rb go from the centres to the contact point, which lies
// midway between the two surfaces; gap is the distance between the surfaces
// along n (negative when they overlap).
template <class T>
struct ContactGeometry {
  math::Vector3<T> n, ra, rb;
  T gap;
};

namespace detail {
// Contact point p = q + n gap / 2, q the closest point on b's surface.
template <class T>
GPUSOLVE_HD ContactGeometry<T> contact_at(const math::Vector3<T>& q, const math::Vector3<T>& n, T gap,
                                          const math::Vector3<T>& pa, const math::Vector3<T>& pb) {
  const math::Vector3<T> p = q + (gap / 2) * n;
  return {n, p - pa, p - pb, gap};
}
}  // namespace detail

// Spheres of radii Ra at pa and Rb at pb. Coincident centres get the normal +z.
template <class T>
GPUSOLVE_HD ContactGeometry<T> sphere_sphere(const math::Vector3<T>& pa, T Ra, const math::Vector3<T>& pb,
                                             T Rb) {
  const math::Vector3<T> d = pa - pb;
  const T dist = math::norm(d);
  const math::Vector3<T> n = dist > T(0) ? math::Vector3<T>(d * (T(1) / dist)) : math::Vector3<T>(T(0), T(0), T(1));
  return detail::contact_at<T>(pb + Rb * n, n, dist - Ra - Rb, pa, pb);
}

// A sphere against the plane n.x = d (solid below), whose reference point is pb.
template <class T>
GPUSOLVE_HD ContactGeometry<T> sphere_plane(const math::Vector3<T>& pa, T Ra, const math::Vector3<T>& n, T d,
                                            const math::Vector3<T>& pb) {
  const T height = math::dot(n, pa) - d;
  return detail::contact_at<T>(pa - height * n, n, height - Ra, pa, pb);
}

// A sphere against a box with centre pb, rotation R (body -> world) and half
// extents h. Outside the box the normal runs from the closest point of the box
// (on a face, edge or corner) to the centre; a centre inside the box is pushed
// out through the nearest face.
template <class T>
GPUSOLVE_HD ContactGeometry<T> sphere_box(const math::Vector3<T>& pa, T Ra, const math::Vector3<T>& pb,
                                          const math::Matrix3x3<T>& R, const math::Vector3<T>& h) {
  const math::Vector3<T> c = math::transpose(R) * (pa - pb);  // sphere centre in the box frame
  math::Vector3<T> q;
  for (int k = 0; k < 3; ++k) q[k] = c[k] < -h[k] ? -h[k] : (c[k] > h[k] ? h[k] : c[k]);
  const math::Vector3<T> out = c - q;
  const T dist = math::norm(out);
  math::Vector3<T> n_local;
  T depth;  // signed distance of the centre from the box surface
  if (dist > T(0)) {
    n_local = out * (T(1) / dist);
    depth = dist;
  } else {
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (h[j] - std::fabs(c[j]) < h[k] - std::fabs(c[k])) k = j;
    const T s = c[k] < T(0) ? T(-1) : T(1);
    n_local[k] = s;
    q[k] = s * h[k];
    depth = -(h[k] - std::fabs(c[k]));
  }
  const math::Vector3<T> n = R * n_local;
  const math::Vector3<T> qw = pb + R * q;
  return detail::contact_at<T>(qw, n, depth - Ra, pa, pb);
}

}  // namespace gpusolve::rbd
