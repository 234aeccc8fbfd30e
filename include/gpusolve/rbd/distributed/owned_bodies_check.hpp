// OwnedBodiesCheck: what a rank of a distributed world learns from its World's
// bodies after a step, found where the bodies live in one reduction: whether
// any body it owns must move between ranks before the next step (it went
// farther than the skin past its cell, came within reach of a rank that holds
// no shadow of it, or holds a NaN), and the figures of its own bodies. A step
// that moves no body so reads back a few numbers, not the bodies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/math.hpp"
#include "gpusolve/rbd/bodies/validation.hpp"
#include "gpusolve/rbd/distributed/rank_grid.hpp"
#include "gpusolve/rbd/execution/backend.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"
#include "gpusolve/rbd/statistics/accuracy.hpp"

namespace gpusolve::rbd {

// A rank's own (active) bodies after a step: their count, kinetic energy and
// momentum, summed in double, and how many must move between ranks.
struct OwnedBodies {
  double count = 0, kinetic_energy = 0, momentum[3] = {0, 0, 0};
  std::uint32_t to_move = 0;
};

namespace detail {

// Body k's share of OwnedBodies; only active bodies (this rank's own) count.
// Its shadows were sent within its bound + reach + 2 skin of where it was, so
// while every body stays within the skin of its owner's cell and each needs
// shadows (bound + reach + skin) only where it has them, every contact's two
// bodies are still on the rank that solves it (docs/distributed.md).
template <class BV, class T>
struct OwnedBodyFigures {
  BV b;
  RankGrid<T> grid;
  int rank;
  T reach;                            // a body's bound plus this is the farthest it makes contacts
  T skin;                             // how far a body may go past its cell before it moves
  const std::uint64_t* shadowed_at;   // per body: the ranks holding its shadow (RankGrid::ranks_within)
  GPUSOLVE_HD OwnedBodies operator()(std::size_t k) const {
    OwnedBodies f;
    if (b.status[k] != active) return f;
    const typename RankGrid<T>::Vec x{b.pos(k, 0), b.pos(k, 1), b.pos(k, 2)};
    const T bound = shape_bound<T>(b.shape[k], b.shape_param(k, 0), b.shape_param(k, 1), b.shape_param(k, 2));
    const bool finite = NonFiniteKey<BV>{b}(k) == ~std::uint64_t(0);
    const bool unshadowed = (grid.ranks_within(x, bound + reach + skin, rank) & ~shadowed_at[k]) != 0;
    f.to_move = !finite || !grid.near(x, rank, skin) || unshadowed;
    f.count = 1;
    f.kinetic_energy = double(KineticEnergy<BV, T>{b}(k));
    for (int a = 0; a < 3; ++a) f.momentum[a] = double(b.v(k, a)) / double(b.inv_mass[k]);
    return f;
  }
};

struct CombineOwned {
  GPUSOLVE_HD OwnedBodies operator()(const OwnedBodies& x, const OwnedBodies& y) const {
    OwnedBodies s;
    s.count = x.count + y.count;
    s.kinetic_energy = x.kinetic_energy + y.kinetic_energy;
    for (int a = 0; a < 3; ++a) s.momentum[a] = x.momentum[a] + y.momentum[a];
    s.to_move = x.to_move + y.to_move;
    return s;
  }
};

}  // namespace detail

template <class Device, class T>
class OwnedBodiesCheck {
 public:
  // Per body of the World: the ranks that hold its shadow (0 for a body it
  // does not own), as the rank sent them at its last exchange of bodies.
  void shadowed_at(const std::vector<std::uint64_t>& ranks) {
    shadowed_at_.resize(ranks.size());
    detail::copy_with_host<Device>(shadowed_at_.data(), ranks.data(), ranks.size(), false, stream_t{});
  }

  // The figures of the bodies b (the World's, on the backend) for this rank
  // of `grid`; waits for them.
  template <class BV>
  OwnedBodies run(const BV& b, const RankGrid<T>& grid, int rank, T reach, T skin) {
    if (out_.size_x() == 0) out_.resize(1);
    algorithms_.reduce_into(b.size(), detail::OwnedBodyFigures<BV, T>{b, grid, rank, reach, skin, shadowed_at_.data()},
                            OwnedBodies{}, detail::CombineOwned{}, out_.data(), stream_t{});
    return detail::read_back<Device>(out_.data(), 0, stream_t{});
  }

 private:
  VectorD1<std::uint64_t, device_is<Device>> shadowed_at_;
  VectorD1<OwnedBodies, device_is<Device>> out_;
  detail::DeviceAlgorithms<Device> algorithms_;
};

}  // namespace gpusolve::rbd
