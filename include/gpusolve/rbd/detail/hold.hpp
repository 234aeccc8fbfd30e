// UnlessHeld: a kernel's functor that does nothing while its step is held.
#pragma once

#include <cstddef>
#include <cstdint>

#include "gpusolve/core/config.hpp"

namespace gpusolve::rbd::detail {

// f(i), unless *hold is not 0: a word of the backend's memory that an earlier
// kernel of the stream set because the step must not be taken (World::
// advance_unattended: a contact list too small, a body not finite). nullptr:
// never held.
template <class F>
struct UnlessHeld {
  F f;
  const std::uint32_t* hold;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (hold == nullptr || *hold == 0) f(i);
  }
};

}  // namespace gpusolve::rbd::detail
