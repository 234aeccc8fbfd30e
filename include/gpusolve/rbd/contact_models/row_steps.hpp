// Which of a contact model's rows share one step of the diagonal solve
// (InverseBlocks): the contacts store one value per step, not per row.
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd {

// The normal row steps alone; the two friction rows share one step, so the
// cone's disc keeps its shape; an angular model's torsional row steps alone
// and its two rolling rows share one, as the friction rows do.
template <class Model>
inline constexpr std::size_t row_steps =
    (Model::linear_rows == 3 ? 2 : 1) + (Model::rows > Model::linear_rows ? 2 : 0);

// The step that row r of Model takes.
template <class Model>
GPUSOLVE_HD constexpr std::size_t row_step(std::size_t r) {
  constexpr std::size_t L = Model::linear_rows, linear_steps = L == 3 ? 2 : 1;
  return r < L ? (r == 0 ? 0 : 1) : linear_steps + (r == L ? 0 : 1);
}

}  // namespace gpusolve::rbd
