// Steps queued with no host wait (World::advance_unattended): the hold word
// their kernels read, the count of steps taken, and what finish() settles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/rbd/execution/backend.hpp"

namespace gpusolve::rbd::detail {

// f(i), unless *hold is not 0: a word of the backend's memory that an earlier
// kernel of the stream set because the step must not be taken (a contact list
// too small, a body not finite). nullptr: never held.
template <class F>
struct UnlessHeld {
  F f;
  const std::uint32_t* hold;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (hold == nullptr || *hold == 0) f(i);
  }
};

// UnlessHeld for the last kernel of a step, which also counts the step taken
// (index 0, in word[1]). word: UnattendedSteps::hold(), or nullptr.
template <class F>
struct CountedUnlessHeld {
  F f;
  std::uint32_t* word;
  GPUSOLVE_HD void operator()(std::size_t i) const {
    if (word != nullptr) {
      if (word[0] != 0) return;
      if (i == 0) ++word[1];
    }
    f(i);
  }
};

}  // namespace gpusolve::rbd::detail

namespace gpusolve::rbd {

// The bookkeeping of unattended steps: a word pair {hold, steps taken} in the
// backend's memory, the first step not yet settled, and the steps queued again.
template <class Device>
class UnattendedSteps {
 public:
  // Steps from `first_step` on are queued unattended (the earliest one counts
  // while earlier ones are still unsettled).
  void begin(std::size_t first_step, stream_t stream) {
    if (word_.size_x() == 0) {
      word_.resize(2);
      word_.fill(0u, stream);
    }
    if (!pending_) first_ = first_step;
    pending_ = true;
  }
  // The word pair the kernels of an unattended step read and write.
  std::uint32_t* hold() { return word_.data(); }
  bool pending() const { return pending_; }

  // Waits for the queued steps. Returns the first step that was held (it and
  // every step after it changed nothing), after clearing the hold; or nothing.
  std::optional<std::size_t> settle(stream_t stream) {
    pending_ = false;
    const std::uint32_t held = detail::read_back<Device>(word_.data(), 0, stream);
    const std::uint32_t taken_total = detail::read_back<Device>(word_.data(), 1, stream);
    const std::size_t taken = std::uint32_t(taken_total - taken_seen_);  // modulo 2^32, as the counter
    taken_seen_ = taken_total;
    if (held == 0) return std::nullopt;
    word_.fill(0u, stream);
    taken_seen_ = 0;
    return first_ + taken;
  }

  // Steps queued again after a hold, as of the last settle.
  void count_requeued(std::size_t steps) { requeued_ += steps; }
  std::size_t requeued() const { return requeued_; }

 private:
  VectorD1<std::uint32_t, device_is<Device>> word_;  // {hold, steps taken}
  std::uint32_t taken_seen_ = 0;                     // steps taken at the last settle
  std::size_t first_ = 0, requeued_ = 0;
  bool pending_ = false;
};

}  // namespace gpusolve::rbd
