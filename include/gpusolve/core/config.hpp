// Compiler and toolkit detection shared by every gpusolve header.
#pragma once

#include <cstddef>

// Functions that run on both backends are marked GPUSOLVE_HD. Under a plain
// C++ compiler the marker expands to nothing, so the same bodies build with g++.
#if defined(__CUDACC__)
#define GPUSOLVE_HD __host__ __device__
#define GPUSOLVE_HAS_NVCC 1
#else
#define GPUSOLVE_HD
#define GPUSOLVE_HAS_NVCC 0
#endif

// Put before a GPUSOLVE_HD function template that calls, for some of its
// template arguments, a host-only function (a kernel launch): nvcc then checks
// each instantiation where it is used instead of warning about the template.
#if defined(__CUDACC__)
#define GPUSOLVE_EXEC_CHECK_DISABLE _Pragma("nv_exec_check_disable")
#else
#define GPUSOLVE_EXEC_CHECK_DISABLE
#endif

// Put before a loop of fixed trip count whose iterations' loads should all be
// in flight at once: nvcc unrolls it; host compilers decide for themselves.
#if defined(__CUDACC__)
#define GPUSOLVE_UNROLL _Pragma("unroll")
#else
#define GPUSOLVE_UNROLL
#endif

// Put before a loop whose body should stay one copy in a kernel that holds
// many (nvcc would otherwise unroll a short loop and give every copy registers).
#if defined(__CUDACC__)
#define GPUSOLVE_NO_UNROLL _Pragma("unroll 1")
#else
#define GPUSOLVE_NO_UNROLL
#endif

// The CUDA runtime API (memory, streams, events) is usable from plain C++ when
// its header is on the include path; kernels need nvcc (GPUSOLVE_HAS_NVCC).
// Define GPUSOLVE_NO_CUDART to build a strictly CPU-only program.
#if !defined(GPUSOLVE_NO_CUDART) && (defined(__CUDACC__) || __has_include(<cuda_runtime_api.h>))
#define GPUSOLVE_HAS_CUDART 1
#include <cuda_runtime_api.h>
#else
#define GPUSOLVE_HAS_CUDART 0
#endif

// Put before a large GPUSOLVE_HD function that several kernels or call sites
// share: on the device it stays one called function rather than a copy
// inlined at each site, which keeps kernels and their compile time small
// (docs/build_time.md); host compilers decide for themselves.
#if defined(__CUDACC__)
#define GPUSOLVE_HD_NOINLINE __host__ __device__ __noinline__
#else
#define GPUSOLVE_HD_NOINLINE
#endif

// True only while compiling device code.
#if defined(__CUDA_ARCH__)
#define GPUSOLVE_DEVICE_CODE 1
#else
#define GPUSOLVE_DEVICE_CODE 0
#endif

namespace gpusolve {

#if GPUSOLVE_HAS_CUDART
using stream_t = cudaStream_t;
#else
// Stand-in so that signatures taking a stream compile without the toolkit.
using stream_t = void*;
#endif

}  // namespace gpusolve

// NCCL, for a distributed world's exchange from GPU to GPU
// (rbd/distributed/nccl_body_exchange.hpp): a program that links it defines
// GPUSOLVE_WITH_NCCL=1 (CMake's gpusolve::nccl target does).
#if !defined(GPUSOLVE_WITH_NCCL)
#define GPUSOLVE_WITH_NCCL 0
#endif
