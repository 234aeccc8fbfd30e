// The benchmarks' timing kit: CUDA-event stopwatch, order statistics, the GPU/nvcc banner, list options.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "gpusolve/core/config.hpp"
#include "gpusolve/core/error.hpp"

namespace gpusolve::bench {

// Median and spread of repeated measurements.
struct Spread {
  double median = 0, p10 = 0, p90 = 0, min = 0, max = 0;
};

inline Spread spread(std::vector<double> v) {
  if (v.empty()) throw InvalidArgumentError("bench: no measurements");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  // Nearest-rank percentile: with 20 repeats p10 is the 2nd and p90 the 18th value.
  const auto pct = [&](double p) { return v[std::min(n - 1, std::size_t(p * n))]; };
  return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), pct(0.1), pct(0.9), v.front(), v.back()};
}

// Milliseconds between two events recorded around work on one stream.
class EventTimer {
 public:
  explicit EventTimer(cudaStream_t stream) : stream_(stream) {
    GPUSOLVE_CUDA_CHECK(cudaEventCreate(&start_));
    GPUSOLVE_CUDA_CHECK(cudaEventCreate(&stop_));
  }
  ~EventTimer() {
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  EventTimer(const EventTimer&) = delete;
  EventTimer& operator=(const EventTimer&) = delete;
  void start() { GPUSOLVE_CUDA_CHECK(cudaEventRecord(start_, stream_)); }
  double stop_ms() {
    GPUSOLVE_CUDA_CHECK(cudaEventRecord(stop_, stream_));
    GPUSOLVE_CUDA_CHECK(cudaEventSynchronize(stop_));
    GPUSOLVE_CUDA_CHECK(cudaGetLastError());
    float ms = 0;
    GPUSOLVE_CUDA_CHECK(cudaEventElapsedTime(&ms, start_, stop_));
    return ms;
  }

 private:
  cudaStream_t stream_;
  cudaEvent_t start_, stop_;
};

// Prints the GPU, the compiler and the runtime; returns the GPU's name for CSV rows.
inline std::string print_banner(const char* what) {
  int dev = 0, runtime = 0, driver = 0;
  GPUSOLVE_CUDA_CHECK(cudaGetDevice(&dev));
  cudaDeviceProp p{};
  GPUSOLVE_CUDA_CHECK(cudaGetDeviceProperties(&p, dev));
  GPUSOLVE_CUDA_CHECK(cudaRuntimeGetVersion(&runtime));
  GPUSOLVE_CUDA_CHECK(cudaDriverGetVersion(&driver));
  std::printf("%s\nGPU: %s (sm_%d%d, %d SMs, %.0f MB L2)\nnvcc %d.%d.%d, CUDA runtime %d.%d, driver API %d.%d\n", what,
              p.name, p.major, p.minor, p.multiProcessorCount, p.l2CacheSize / 1e6, __CUDACC_VER_MAJOR__,
              __CUDACC_VER_MINOR__, __CUDACC_VER_BUILD__, runtime / 1000, runtime % 1000 / 10, driver / 1000,
              driver % 1000 / 10);
  return p.name;
}

// A comma-separated list of numbers ("26000,1000000", "0.2,0.5").
template <class N>
std::vector<N> parse_list(const std::string& s) {
  std::vector<N> out;
  std::istringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::istringstream one(item);
    N v{};
    if (!(one >> v) || !one.eof()) throw InvalidArgumentError("bench: not a number in list: '" + item + "'");
    out.push_back(v);
  }
  if (out.empty()) throw InvalidArgumentError("bench: empty list");
  return out;
}

// A comma-separated list of words ("apgd,jacobi"); empty words are kept.
inline std::vector<std::string> parse_words(const std::string& s) {
  std::vector<std::string> out;
  std::size_t a = 0;
  for (std::size_t b; (b = s.find(',', a)) != std::string::npos; a = b + 1) out.push_back(s.substr(a, b - a));
  out.push_back(s.substr(a));
  return out;
}

// The value after option argv[i] (advances i); exits with a message if missing.
inline std::string option_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) {
    std::fprintf(stderr, "%s: option %s needs a value\n", argv[0], argv[i]);
    std::exit(2);
  }
  return argv[++i];
}

// Prints the usage line; exits 0 for --help/-h, 2 for anything else unknown.
[[noreturn]] inline void usage_exit(const char* argv0, const char* options, const std::string& arg) {
  std::fprintf(stderr, "usage: %s %s\n", argv0, options);
  std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
}

// Opens `path` for writing and writes the CSV header; nullptr for an empty path.
inline std::FILE* open_csv(const std::string& path, const char* header) {
  if (path.empty()) return nullptr;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw Error("bench: cannot write " + path);
  std::fprintf(f, "%s\n", header);
  return f;
}

}  // namespace gpusolve::bench
