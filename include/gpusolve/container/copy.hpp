// Copies between containers of one rank and element type, on any two of host,
// pinned and device memory, with any two layouts: copy(dst, src) and copy_async.
#pragma once

#include <cstddef>
#include <sstream>
#include <type_traits>

#include "gpusolve/container/vector_storage.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/memory/allocator.hpp"
#include "gpusolve/memory/copy.hpp"
#include "gpusolve/policy/runtime.hpp"
#include "gpusolve/policy/runtime_stopwatch.hpp"

namespace gpusolve {
namespace detail {

template <class Dst, class Src>
void copy_containers(Dst& dst, const Src& src, bool async, stream_t stream) {
  static_assert(Dst::rank == Src::rank, "gpusolve: copies need containers of the same rank");
  static_assert(std::is_same_v<typename Dst::value_type, typename Src::value_type>,
                "gpusolve: copies need containers of the same element type");
  using T = typename Dst::value_type;
  using To = typename Dst::memory_kind;
  using From = typename Src::memory_kind;
  using R = runtime::either<typename Dst::runtime_policy, typename Src::runtime_policy>;

  // Chosen rule: an empty destination takes the source's shape (as
  // thrust::device_vector's assignment does); any other mismatch is an error,
  // because silently reallocating would invalidate views the caller holds.
  if (dst.extents() != src.extents()) {
    if (!dst.empty()) {
      std::ostringstream os;
      os << "gpusolve: cannot copy a " << shape_string(src.extents(), Src::rank) << " container into a "
         << shape_string(dst.extents(), Dst::rank) << " one (logical shapes differ)";
      throw SizeMismatchError(os.str());
    }
    dst.resize_as(src);
  }
  if (src.empty() || static_cast<const void*>(dst.data()) == static_cast<const void*>(src.data())) return;

  constexpr bool touches_device = !memory::is_host_accessible_v<To> || !memory::is_host_accessible_v<From>;
  // Equal padding: one contiguous block (padding is zero on both sides).
  // Otherwise one pitched 2-D copy per z slice, moving only logical elements.
  const bool same_layout = dst.pitch() == src.pitch() && dst.padded_y() == src.padded_y();
  const std::size_t nz = src.size_z();
  const std::size_t logical_bytes = src.size() * sizeof(T);

  auto run = [&] {
    if (same_layout) {
      const std::size_t bytes = src.pitch() * src.padded_y() * nz * sizeof(T);
      memory::copy_rows<To, From>(dst.data(), bytes, src.data(), bytes, bytes, 1, async, stream);
      return;
    }
    const std::size_t dslice = dst.pitch() * dst.padded_y(), sslice = src.pitch() * src.padded_y();
    for (std::size_t k = 0; k < nz; ++k)
      memory::copy_rows<To, From>(dst.data() + k * dslice, dst.pitch() * sizeof(T), src.data() + k * sslice,
                                  src.pitch() * sizeof(T), src.size_x() * sizeof(T), src.size_y(), async,
                                  stream);
  };

  if constexpr (R::performance) {
    runtime::Stopwatch watch(touches_device, stream);
    run();
    runtime::performance_log().add(runtime::CopyRecord{From::name, To::name, logical_bytes, watch.seconds(), async});
  } else {
    run();
  }
  runtime::report_info<R>([&] {
    std::ostringstream os;
    os << "gpusolve: copy " << From::name << " -> " << To::name << ", " << shape_string(src.extents(), Src::rank)
       << " elements of " << sizeof(T) << " bytes (" << logical_bytes << " bytes), "
       << (same_layout ? "one contiguous block" : "pitched rows") << ", row pitch " << src.pitch() * sizeof(T)
       << " -> " << dst.pitch() * sizeof(T) << " bytes" << (async ? ", asynchronous" : "");
    return os.str();
  });
}

}  // namespace detail

// Copies src into dst and returns when the copy is complete.
// Throws SizeMismatchError when the logical shapes differ (an empty dst is resized).
template <class Dst, class Src>
void copy(Dst& dst, const Src& src) {
  detail::copy_containers(dst, src, false, stream_t{});
}

// Queues the copy on `stream` (cudaMemcpy2DAsync); it overlaps with other work
// only when the host side is pinned. Host-to-host copies complete before return.
// Under a performance policy the copy is timed and therefore waited for.
template <class Dst, class Src>
void copy_async(Dst& dst, const Src& src, stream_t stream) {
  detail::copy_containers(dst, src, true, stream);
}

}  // namespace gpusolve
