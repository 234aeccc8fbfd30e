// Typed exceptions for every failure gpusolve reports, and the CUDA call check.
#pragma once

#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gpusolve/core/config.hpp"

namespace gpusolve {

// Base of every exception the library throws.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A CUDA runtime call failed: names the call, the source location and the code.
class CudaError : public Error {
 public:
  CudaError(int code, const std::string& what) : Error(what), code_(code) {}
  int code() const noexcept { return code_; }

 private:
  int code_;
};

// No usable GPU or driver: the GPU backend cannot run on this machine.
class NoDeviceError : public CudaError {
 public:
  using CudaError::CudaError;
};

// An allocation failed; carries the number of bytes that were requested.
class OutOfMemoryError : public Error {
 public:
  OutOfMemoryError(std::size_t bytes, const std::string& what) : Error(what), bytes_(bytes) {}
  std::size_t requested_bytes() const noexcept { return bytes_; }

 private:
  std::size_t bytes_;
};

// Two containers (or a container and an argument) disagree on their shape.
class SizeMismatchError : public Error {
 public:
  using Error::Error;
};

// An index outside a container's logical extents (debug policy only).
class BoundsError : public Error {
 public:
  using Error::Error;
};

// An argument or a piece of state is outside what the callee accepts.
class InvalidArgumentError : public Error {
 public:
  using Error::Error;
};

// The operation needs something this build does not have (nvcc, the CUDA runtime).
class UnsupportedError : public Error {
 public:
  using Error::Error;
};

#if GPUSOLVE_HAS_CUDART
namespace detail {

inline bool is_no_device(cudaError_t e) {
  return e == cudaErrorNoDevice || e == cudaErrorInsufficientDriver ||
         e == cudaErrorInvalidDevice || e == cudaErrorDevicesUnavailable ||
         e == cudaErrorSystemDriverMismatch || e == cudaErrorCompatNotSupportedOnDevice;
}

inline std::string cuda_message(cudaError_t e, const char* call, const char* file, int line) {
  std::ostringstream os;
  os << "gpusolve: CUDA call `" << call << "` failed at " << file << ':' << line << ": "
     << cudaGetErrorName(e) << " (" << cudaGetErrorString(e) << ')';
  return os.str();
}

[[noreturn]] inline void throw_cuda(cudaError_t e, const char* call, const char* file, int line) {
  // A failed call leaves a sticky-free error behind; clear it so the next check
  // reports its own call, not this one.
  (void)cudaGetLastError();
  const std::string msg = cuda_message(e, call, file, line);
  if (is_no_device(e)) throw NoDeviceError(static_cast<int>(e), msg + " [no usable GPU]");
  throw CudaError(static_cast<int>(e), msg);
}

inline void check_cuda(cudaError_t e, const char* call, const char* file, int line) {
  if (e != cudaSuccess) throw_cuda(e, call, file, line);
}

}  // namespace detail

// Checks one CUDA runtime call and throws CudaError (NoDeviceError without a GPU).
#define GPUSOLVE_CUDA_CHECK(call) ::gpusolve::detail::check_cuda((call), #call, __FILE__, __LINE__)
#endif

}  // namespace gpusolve
