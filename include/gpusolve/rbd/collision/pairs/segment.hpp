// Segment helpers for the capsule pairs: closest points on segments (after
// Ericson, Real-Time Collision Detection, 5.1.2 and 5.1.9).
#pragma once

#include <cmath>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"

namespace gpusolve::rbd {

namespace detail {

template <class T>
GPUSOLVE_HD T clamp_to(T v, T lo, T hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

}  // namespace detail

// A unit vector perpendicular to u (|u| > 0): the fallback normal where two
// closest points coincide, so that degenerate contacts never give NaN.
template <class T>
GPUSOLVE_HD math::Vector3<T> unit_perpendicular(const math::Vector3<T>& u) {
  const T ax = std::fabs(u[0]), ay = std::fabs(u[1]), az = std::fabs(u[2]);
  // Cross with the coordinate axis least aligned with u: the best conditioned choice.
  const math::Vector3<T> e = (ax <= ay && ax <= az) ? math::Vector3<T>(T(1), T(0), T(0))
                             : (ay <= az)           ? math::Vector3<T>(T(0), T(1), T(0))
                                                    : math::Vector3<T>(T(0), T(0), T(1));
  const math::Vector3<T> c = u % e;
  const T len = math::norm(c);
  return len > T(0) ? math::Vector3<T>(c * (T(1) / len)) : math::Vector3<T>(T(0), T(0), T(1));
}

// Parameter t in [0, 1] of the point p + t (q - p) closest to c; a segment of
// zero length gives t = 0.
template <class T>
GPUSOLVE_HD T segment_closest_param(const math::Vector3<T>& p, const math::Vector3<T>& q,
                                    const math::Vector3<T>& c) {
  const math::Vector3<T> d = q - p;
  const math::Vector3<T> pc = c - p;
  const T dd = math::dot(d, d);
  return dd > T(0) ? detail::clamp_to(math::dot(pc, d) / dd, T(0), T(1)) : T(0);
}

// The point of segment pq closest to c.
template <class T>
GPUSOLVE_HD math::Vector3<T> segment_closest_point(const math::Vector3<T>& p, const math::Vector3<T>& q,
                                                   const math::Vector3<T>& c) {
  const T t = segment_closest_param(p, q, c);
  const math::Vector3<T> d = q - p;
  return math::Vector3<T>(p + t * d);
}

// The closest points c1 = p1 + s (q1 - p1) and c2 = p2 + t (q2 - p2) of two
// segments, and their squared distance.
template <class T>
struct SegmentClosest {
  T s, t;
  math::Vector3<T> c1, c2;
  T dist2;
};

// Closest points of segments p1q1 and p2q2 (Ericson 5.1.9). Nearly parallel
// segments, where the interior solution is ill-conditioned, also try the four
// edges of the (s, t) square, each an exact 1D clamp, and keep the best: the
// distance is then exact however parallel the segments are.
template <class T>
GPUSOLVE_HD SegmentClosest<T> segment_segment_closest(const math::Vector3<T>& p1, const math::Vector3<T>& q1,
                                                      const math::Vector3<T>& p2, const math::Vector3<T>& q2) {
  using V = math::Vector3<T>;
  const V d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const T a = math::dot(d1, d1), e = math::dot(d2, d2), f = math::dot(d2, r);
  const T tiny = T(1e-12) * (a + e + math::dot(r, r));  // a segment shorter than this is a point
  const auto dist2_at = [&](T s, T t) {
    const V c1 = p1 + s * d1, c2 = p2 + t * d2;
    const V d = c1 - c2;
    return math::dot(d, d);
  };
  T s = T(0), t = T(0);
  if (a <= tiny && e <= tiny) {
  } else if (a <= tiny) {
    t = detail::clamp_to(f / e, T(0), T(1));
  } else {
    const T c = math::dot(d1, r);
    if (e <= tiny) {
      s = detail::clamp_to(-c / a, T(0), T(1));
    } else {
      const T b = math::dot(d1, d2);
      const T denom = a * e - b * b;  // >= 0; zero when parallel
      s = denom > T(0) ? detail::clamp_to((b * f - c * e) / denom, T(0), T(1)) : T(0);
      t = (b * s + f) / e;
      if (t < T(0)) {
        t = T(0);
        s = detail::clamp_to(-c / a, T(0), T(1));
      } else if (t > T(1)) {
        t = T(1);
        s = detail::clamp_to((b - c) / a, T(0), T(1));
      }
      if (denom <= T(1e-4) * a * e) {  // within about 0.6 degrees of parallel
        T best = dist2_at(s, t);
        const T cs[4] = {T(0), T(1), detail::clamp_to(-c / a, T(0), T(1)), detail::clamp_to((b - c) / a, T(0), T(1))};
        const T ct[4] = {detail::clamp_to(f / e, T(0), T(1)), detail::clamp_to((b + f) / e, T(0), T(1)), T(0), T(1)};
        for (int k = 0; k < 4; ++k) {
          const T d2k = dist2_at(cs[k], ct[k]);
          if (d2k < best) {
            best = d2k;
            s = cs[k];
            t = ct[k];
          }
        }
      }
    }
  }
  SegmentClosest<T> out;
  out.s = s;
  out.t = t;
  out.c1 = V(p1 + s * d1);
  out.c2 = V(p2 + t * d2);
  const V d = out.c1 - out.c2;
  out.dist2 = math::dot(d, d);
  return out;
}

}  // namespace gpusolve::rbd
