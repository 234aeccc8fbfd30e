// CompoundType: a compound's parts and mass properties, stored once in a
// BodySet and shared by every body made of it (a DEM clump template).
#pragma once

#include <array>
#include <cstdint>

namespace gpusolve::rbd {

// What BodySet::add_compound_type returns and add_compound(pos, type, q)
// reads: the parts are the BodySet's parts() rows [first_part, first_part +
// count), placed relative to the centre of mass.
template <class T = float>
struct CompoundType {
  std::uint32_t first_part = 0;
  std::uint32_t count = 0;
  T bound = 0;    // bounding radius about the centre of mass
  T feature = 0;  // the smallest feature size of the parts
  T mass = 0;
  std::array<T, 9> inertia{};      // about the centre of mass, in the type's frame
  std::array<T, 9> inv_inertia{};  // its inverse, computed once for every body of the type
  std::array<T, 3> centre{};   // the centre of mass in the frame the parts were given in
};

}  // namespace gpusolve::rbd
