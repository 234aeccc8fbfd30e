// Compile-time policies: chosen per container instance, never by a macro.
#pragma once

namespace gpusolve::compiletime {

// No checks: element access compiles to a plain load or store.
struct ReleasePolicy {
  static constexpr bool bounds_check = false;
};

// Bounds checks on every element access: the host throws BoundsError naming the
// indices and extents, the device prints them and traps.
struct DebugPolicy {
  static constexpr bool bounds_check = true;
};

}  // namespace gpusolve::compiletime
