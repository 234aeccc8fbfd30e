// The bounds check used by container views under compiletime::DebugPolicy.
#pragma once

#include <cstddef>
#include <cstdio>
#include <sstream>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::detail {

// Reports an access to (i, j, k) outside extents (nx, ny, nz); `rank` says how
// many of them are meaningful. Throws on the host, traps on the device.
GPUSOLVE_HD inline void bounds_violation(int rank, std::size_t i, std::size_t j, std::size_t k,
                                         std::size_t nx, std::size_t ny, std::size_t nz) {
#if GPUSOLVE_DEVICE_CODE
  printf("gpusolve: index (%llu, %llu, %llu) out of bounds for extents (%llu, %llu, %llu), rank %d\n",
         (unsigned long long)i, (unsigned long long)j, (unsigned long long)k,
         (unsigned long long)nx, (unsigned long long)ny, (unsigned long long)nz, rank);
  __trap();
#else
  std::ostringstream os;
  const std::size_t idx[3] = {i, j, k};
  const std::size_t ext[3] = {nx, ny, nz};
  os << "gpusolve: index (";
  for (int d = 0; d < rank; ++d) os << (d ? ", " : "") << idx[d];
  os << ") out of bounds for extents (";
  for (int d = 0; d < rank; ++d) os << (d ? ", " : "") << ext[d];
  os << ')';
  throw BoundsError(os.str());
#endif
}

}  // namespace gpusolve::detail
