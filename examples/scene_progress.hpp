// Progress: the status line of a long run on stderr ('\r'-refreshed on a terminal, else every N steps).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace scenes {

// What the line shows about the latest step.
struct ProgressSample {
  long step;             // 0-based index of the step just done
  double time;           // simulated seconds after it
  std::size_t bodies, contacts, iterations;
  double residual, penetration;
};

class Progress {
 public:
  Progress(std::string scene, long steps, long every, bool quiet)
      : scene_(std::move(scene)), steps_(steps), every_(every), quiet_(quiet),
        tty_(isatty(fileno(stderr)) != 0), start_(clock::now()), last_(start_) {}

  void update(const ProgressSample& s) {
    if (quiet_) return;
    const auto now = clock::now();
    const bool last = s.step + 1 == steps_;
    // A terminal is redrawn at most 10 times a second; a log gets a line every N steps.
    if (tty_ ? (!last && now - last_ < std::chrono::milliseconds(100)) : (!last && (s.step + 1) % every_ != 0))
      return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = (s.step + 1) / std::max(elapsed, 1e-9);
    std::fprintf(stderr,
                 "%s%s step %ld/%ld t=%.3fs bodies %zu contacts %zu it %zu res %.2e pen %.3f %.1f steps/s left %s%s",
                 tty_ ? "\r" : "", scene_.c_str(), s.step + 1, steps_, s.time, s.bodies, s.contacts, s.iterations,
                 s.residual, s.penetration, rate, duration((steps_ - s.step - 1) / rate).c_str(),
                 tty_ ? (last ? "\n" : "\033[K") : "\n");
    std::fflush(stderr);
  }

  double elapsed() const { return std::chrono::duration<double>(clock::now() - start_).count(); }

  static std::string duration(double seconds) {
    const long s = static_cast<long>(seconds + 0.5);
    char buf[32];
    if (s >= 3600)
      std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, s / 60 % 60);
    else
      std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
    return buf;
  }

 private:
  using clock = std::chrono::steady_clock;
  std::string scene_;
  long steps_, every_;
  bool quiet_, tty_;
  clock::time_point start_, last_;
};

}  // namespace scenes
