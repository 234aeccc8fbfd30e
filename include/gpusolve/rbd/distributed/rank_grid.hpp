// RankGrid: the subdomains of a distributed world, a Cartesian grid of ranks
// over a box (HCSITS's decomposition, Preclik and Rüde 2015). Plain C++: no MPI.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

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
  int owner(const Vec& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a) c[a] = cell_along(a, p[a]);
    return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]);
  }

  // The distance from p to rank r's cell (0 inside it).
  T distance(const Vec& p, int r) const {
    const std::array<int, 3> c{r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
    T d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const T below = lower(a, c[a]) - p[a], above = p[a] - upper(a, c[a]);
      const T d = std::max({below, above, T(0)});
      d2 += d * d;
    }
    return std::sqrt(d2);
  }

 private:
  T width(int a) const { return (hi_[a] - lo_[a]) / T(dims_[a]); }
  int cell_along(int a, T x) const {
    if (dims_[a] == 1 || !(x >= lo_[a] + width(a))) return 0;  // NaN goes to the first cell too
    return std::min(dims_[a] - 1, int((x - lo_[a]) / width(a)));
  }
  // Cell c's bounds along axis a; the outer ones are infinite.
  T lower(int a, int c) const { return c == 0 ? -std::numeric_limits<T>::infinity() : lo_[a] + T(c) * width(a); }
  T upper(int a, int c) const {
    return c == dims_[a] - 1 ? std::numeric_limits<T>::infinity() : lo_[a] + T(c + 1) * width(a);
  }

  std::array<int, 3> dims_;
  Vec lo_, hi_;
};

}  // namespace gpusolve::rbd
