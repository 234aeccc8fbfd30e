// RankGrid: the subdomains of a distributed world, a Cartesian grid of ranks
// over a box (HCSITS's decomposition, Preclik and Rüde 2015). Plain C++: no
// MPI; its queries run on the host and in kernels alike.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd {

// dims[0] x dims[1] x dims[2] ranks over the box [lo, hi]; rank r is cell
// (x, y, z) with r = x + dims[0] (y + dims[1] z). The outer cells reach to
// infinity, so every point has an owner: a body that leaves the box stays
// with the cell nearest to it.
template <class T>
class RankGrid {
 public:
  using Vec = std::array<T, 3>;

  RankGrid(std::array<int, 3> dims, const Vec& lo, const Vec& hi) : dims_(dims), lo_(lo), hi_(hi) {
    for (int a = 0; a < 3; ++a) {
      if (dims[a] < 1) throw InvalidArgumentError("gpusolve: RankGrid: every dimension needs at least one rank");
      if (!(hi[a] >= lo[a]) || !std::isfinite(lo[a]) || !std::isfinite(hi[a]))
        throw InvalidArgumentError("gpusolve: RankGrid: the box must be finite, lo <= hi");
    }
  }

  int ranks() const { return dims_[0] * dims_[1] * dims_[2]; }
  const std::array<int, 3>& dims() const { return dims_; }

  // The rank whose cell holds point p.
  GPUSOLVE_HD int owner(const Vec& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a) c[a] = cell_along(a, p[a]);
    return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]);
  }

  // The ranks below `below` whose cells come within `reach` of point p, as
  // bits (rank r: bit r; at most 64 ranks).
  GPUSOLVE_HD std::uint64_t ranks_within(const Vec& p, T reach, int below) const {
    std::uint64_t bits = 0;
    for (int r = 0; r < below; ++r)
      if (squared_distance(p, r) <= reach * reach) bits |= std::uint64_t(1) << r;
    return bits;
  }

 private:
  // The squared distance from p to rank r's cell (0 inside it).
  GPUSOLVE_HD T squared_distance(const Vec& p, int r) const {
    const int c[3] = {r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
    T d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const T below = lower(a, c[a]) - p[a], above = p[a] - upper(a, c[a]);
      const T d = below > above ? (below > T(0) ? below : T(0)) : (above > T(0) ? above : T(0));
      d2 += d * d;
    }
    return d2;
  }
  GPUSOLVE_HD T width(int a) const { return (hi_[a] - lo_[a]) / T(dims_[a]); }
  GPUSOLVE_HD int cell_along(int a, T x) const {
    if (dims_[a] == 1 || !(x >= lo_[a] + width(a))) return 0;  // NaN goes to the first cell too
    const int c = int((x - lo_[a]) / width(a));
    return c < dims_[a] - 1 ? c : dims_[a] - 1;
  }
  // Cell c's bounds along axis a; the outer ones are infinite.
  GPUSOLVE_HD T lower(int a, int c) const { return c == 0 ? -std::numeric_limits<T>::infinity() : lo_[a] + T(c) * width(a); }
  GPUSOLVE_HD T upper(int a, int c) const {
    return c == dims_[a] - 1 ? std::numeric_limits<T>::infinity() : lo_[a] + T(c + 1) * width(a);
  }

  std::array<int, 3> dims_;
  Vec lo_, hi_;
};

}  // namespace gpusolve::rbd
