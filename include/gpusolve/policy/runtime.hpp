// Run-time policies: performance records (bytes and times of copies and launches)
// and information messages (padding, alignment, copies), each facet on or off alone.
#pragma once

#include <cstddef>
#include <functional>
#include <iostream>
#include <mutex>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace gpusolve::runtime {

// A container's runtime policy is any type with these two flags. The facets are
// fixed at compile time, so a container with both off carries no cost; where
// the records and messages go is chosen at run time (performance_log(), set_info_sink()).
template <bool Performance, bool Info>
struct Policy {
  static constexpr bool performance = Performance;
  static constexpr bool info = Info;
};
using Off = Policy<false, false>;
using PerformancePolicy = Policy<true, false>;
using InfoPolicy = Policy<false, true>;
using FullPolicy = Policy<true, true>;

// The facets of two policies together (a copy reports if either side asks).
template <class A, class B>
using either = Policy<A::performance || B::performance, A::info || B::info>;

// One copy: its endpoints' memory kinds, the bytes of logical elements moved and
// the time it took. Copies touching the device are timed with CUDA events and
// waited for, so measuring serializes asynchronous copies.
struct CopyRecord {
  std::string from, to;
  std::size_t bytes = 0;
  double seconds = 0;
  bool async = false;
};

// One kernel launch (or CPU loop) reported through record_launch.
struct LaunchRecord {
  std::string label;
  std::string device;
  std::size_t n = 0;
  double seconds = 0;
};

// Process-wide, thread-safe store of the records.
class PerformanceLog {
 public:
  void add(CopyRecord r) {
    std::lock_guard<std::mutex> lock(mutex_);
    copies_.push_back(std::move(r));
  }
  void add(LaunchRecord r) {
    std::lock_guard<std::mutex> lock(mutex_);
    launches_.push_back(std::move(r));
  }
  std::vector<CopyRecord> copies() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return copies_;
  }
  std::vector<LaunchRecord> launches() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return launches_;
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    copies_.clear();
    launches_.clear();
  }

 private:
  mutable std::mutex mutex_;
  std::vector<CopyRecord> copies_;
  std::vector<LaunchRecord> launches_;
};

inline PerformanceLog& performance_log() {
  static PerformanceLog log;
  return log;
}

using InfoSink = std::function<void(const std::string&)>;

namespace detail {
struct InfoState {
  std::mutex mutex;
  InfoSink sink = [](const std::string& m) { std::clog << m << '\n'; };
};
inline InfoState& info_state() {
  static InfoState s;
  return s;
}
}  // namespace detail

// Where information messages go; std::clog until set. Returns the previous sink.
inline InfoSink set_info_sink(InfoSink sink) {
  auto& s = detail::info_state();
  std::lock_guard<std::mutex> lock(s.mutex);
  return std::exchange(s.sink, std::move(sink));
}
// The stream must outlive its use as the sink.
inline InfoSink set_info_sink(std::ostream& os) {
  return set_info_sink([&os](const std::string& m) { os << m << '\n'; });
}

// Sends one message to the sink when R's information facet is on. The message
// is built only then, so `make` may be costly.
template <class R, class Make>
void report_info(Make&& make) {
  if constexpr (R::info) {
    const std::string msg = make();
    auto& s = detail::info_state();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (s.sink) s.sink(msg);
  }
}

// The launch hook: call it after a launch (with its measured time) to have the
// launch recorded when R's performance facet is on.
template <class R>
void record_launch(LaunchRecord r) {
  if constexpr (R::performance) performance_log().add(std::move(r));
}

}  // namespace gpusolve::runtime
