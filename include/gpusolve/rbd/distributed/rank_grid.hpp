// RankGrid: the subdomains of a distributed world, a Cartesian grid of ranks
// over a box (HCSITS's decomposition, Preclik and Rüde 2015). Plain C++: no
// MPI; its queries run on the host and in kernels alike.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::rbd {

// dims[0] x dims[1] x dims[2] ranks over the box [lo, hi]; rank r is cell
// (x, y, z) with r = x + dims[0] (y + dims[1] z). The outer cells reach to
// infinity, so every point has an owner: a body that leaves the box stays
// with the cell nearest to it. `reach` is the farthest a point will be asked
// about (ranks_within): a cell's neighbourhood spans the cells that close to
// it, at most 64 of them, whatever the number of ranks.
template <class T>
class RankGrid {
 public:
  using Vec = std::array<T, 3>;

  RankGrid(std::array<int, 3> dims, const Vec& lo, const Vec& hi, T reach) : dims_(dims), lo_(lo), hi_(hi) {
    for (int a = 0; a < 3; ++a) {
      if (dims[a] < 1) throw InvalidArgumentError("gpusolve: RankGrid: every dimension needs at least one rank");
      if (!(hi[a] >= lo[a]) || !std::isfinite(lo[a]) || !std::isfinite(hi[a]))
        throw InvalidArgumentError("gpusolve: RankGrid: the box must be finite, lo <= hi");
    }
    if (!(reach >= 0) || !std::isfinite(reach))
      throw InvalidArgumentError("gpusolve: RankGrid: the reach must be non-negative and finite");
    int cells = 1;
    for (int a = 0; a < 3; ++a) {
      // A cell d away along a lies beyond d - 1 inner cells, each `width` wide,
      // so it is within reach only if (d - 1) width <= reach.
      const T away = width(a) > T(0) ? std::floor(reach / width(a)) + T(1) : T(dims[a]);
      span_[a] = int(std::fmin(away, T(dims[a] - 1)));
      cells *= 2 * span_[a] + 1;
    }
    if (cells > 64)
      throw UnsupportedError("gpusolve: RankGrid: a body's reach spans " + std::to_string(cells) +
                             " cells, more than 64: use fewer ranks, or a larger box per rank");
  }

  int ranks() const { return dims_[0] * dims_[1] * dims_[2]; }
  const std::array<int, 3>& dims() const { return dims_; }

  // The rank whose cell holds point p.
  GPUSOLVE_HD int owner(const Vec& p) const {
    std::array<int, 3> c;
    for (int a = 0; a < 3; ++a) c[a] = cell_along(a, p[a]);
    return rank_of(c);
  }

  // The ranks below `rank` whose cells come within `reach` (at most the
  // grid's) of point p in rank's cell, as bits over rank's neighbourhood
  // (neighbour() turns a bit back into its rank).
  GPUSOLVE_HD std::uint64_t ranks_within(const Vec& p, T reach, int rank) const {
    std::uint64_t bits = 0;
    const std::array<int, 3> home = cell(rank);
    int bit = 0;
    for (int dz = -span_[2]; dz <= span_[2]; ++dz)
      for (int dy = -span_[1]; dy <= span_[1]; ++dy)
        for (int dx = -span_[0]; dx <= span_[0]; ++dx, ++bit) {
          const std::array<int, 3> c{home[0] + dx, home[1] + dy, home[2] + dz};
          if (c[0] < 0 || c[0] >= dims_[0] || c[1] < 0 || c[1] >= dims_[1] || c[2] < 0 || c[2] >= dims_[2]) continue;
          const int r = rank_of(c);
          if (r < rank && squared_distance(p, r) <= reach * reach) bits |= std::uint64_t(1) << bit;
        }
    return bits;
  }

  // Whether point p lies within distance d of rank's cell (inside it: 0).
  GPUSOLVE_HD bool near(const Vec& p, int rank, T d) const { return squared_distance(p, rank) <= d * d; }

  // The rank of bit `bit` of rank's neighbourhood (ranks_within).
  int neighbour(int rank, int bit) const {
    const int across[3] = {2 * span_[0] + 1, 2 * span_[1] + 1, 2 * span_[2] + 1};
    const std::array<int, 3> home = cell(rank);
    return rank_of({home[0] + bit % across[0] - span_[0], home[1] + (bit / across[0]) % across[1] - span_[1],
                    home[2] + bit / (across[0] * across[1]) - span_[2]});
  }

 private:
  // The squared distance from p to rank r's cell (0 inside it).
  GPUSOLVE_HD T squared_distance(const Vec& p, int r) const {
    const std::array<int, 3> c = cell(r);
    T d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const T below = lower(a, c[a]) - p[a], above = p[a] - upper(a, c[a]);
      const T d = below > above ? (below > T(0) ? below : T(0)) : (above > T(0) ? above : T(0));
      d2 += d * d;
    }
    return d2;
  }
  // Rank r's cell, and the rank of cell c.
  GPUSOLVE_HD std::array<int, 3> cell(int r) const {
    return {r % dims_[0], (r / dims_[0]) % dims_[1], r / (dims_[0] * dims_[1])};
  }
  GPUSOLVE_HD int rank_of(const std::array<int, 3>& c) const { return c[0] + dims_[0] * (c[1] + dims_[1] * c[2]); }
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
  int span_[3] = {0, 0, 0};  // the neighbourhood: cells this many away along each axis
};

}  // namespace gpusolve::rbd
