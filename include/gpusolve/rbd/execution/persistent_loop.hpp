// PersistentLoop: runs many iterations of a solver in one cooperative kernel,
// a grid-wide barrier between their phases instead of a kernel launch each.
//
// An iteration program is a __host__ __device__ callable program(e, k, last)
// that queues the phases of a run's k-th iteration (k = 1, 2, ...; `last` for
// the run's last) through an executor e: e.each(n, f) runs f(i) for i in
// [0, n); e.sync() orders everything before it before everything after it;
// e.reduce(n, f, init, op, out) writes init op f(0) op ... op f(n - 1) to *out,
// which index 0 of the next e.each reads at once and every index after the next
// e.sync() (the reduction costs one barrier, not two), and e.sum(n, f, out) is
// its sum; e.scan(in, out, n) writes the inclusive prefix sums of the
// std::uint32_t in[0, n) to out, read after the next e.sync(). It ends with
// e.sync(). A start program start(e) queues phases the same way, before the
// first iteration of a run, and ends with e.sync() if it queued any. The same
// programs run under two executors: LaunchExec (launch_exec.hpp, a launch per
// phase, both backends) and GridExec here (phases of one kernel, GPU). A phase
// is the same functor either way. run() queues a fixed number of iterations;
// run_checked() a whole solve, its residual checks, stopping rule and retries
// applied inside the kernel, so the host needs to wait for nothing but its verdict.
// A grid small enough for one thread-block cluster (sm_90 and later, at most
// 16 blocks) is launched as that cluster, and its phases are separated by the
// cluster's hardware barrier instead of the grid's barrier through global memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "gpusolve/container/vector_d1.hpp"
#include "gpusolve/core/config.hpp"
#include "gpusolve/core/device.hpp"
#include "gpusolve/core/device_facts.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/rbd/execution/device_algorithms.hpp"

#if GPUSOLVE_HAS_NVCC
#include <cooperative_groups.h>
#include <cub/block/block_reduce.cuh>
#include <cub/block/block_scan.cuh>
#endif

namespace gpusolve::rbd::detail {

inline constexpr unsigned persistent_block_size = 256;

// The largest thread-block cluster a persistent kernel is launched as (the
// non-portable limit of sm_90; the portable one is 8).
inline constexpr unsigned persistent_max_cluster = 16;

#if GPUSOLVE_HAS_NVCC
// The barriers between a persistent kernel's phases: the whole grid's through
// global memory (a cooperative launch), or, where the grid is one thread-block
// cluster, the cluster's in hardware. Both order the global memory accesses
// before them before those after them, for every thread of the grid.
// A grid of one block (a scene of up to 256 contacts and bodies) takes the
// block's barrier, which orders its threads' global accesses as well: the
// grid's and the cluster's release is a GPU-wide fence (MEMBAR.ALL.GPU) and
// their acquire empties L1 (CCTL.IVALL), so every load after them went to L2.
__device__ inline bool one_block_grid() { return gridDim.x == 1; }
struct GridBarrier {
  __device__ static void sync() {
    if (one_block_grid())
      __syncthreads();
    else
      cooperative_groups::this_grid().sync();
  }
};
struct ClusterBarrier {
  __device__ static void sync() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ < 900
    __trap();  // never launched: the host launches clusters only for sm_90 binaries
#else
    if (one_block_grid())
      __syncthreads();
    else
      cooperative_groups::this_cluster().sync();
#endif
  }
};

// The executor inside the persistent kernel. Its sum is deterministic: each
// block reduces its strided share, block 0 adds the blocks' partials in order.
// Its scan: each block scans a contiguous share, then adds the totals of the
// blocks before it.
template <class T, class Barrier>
struct GridExec {
  T* partials;                 // one per block
  std::uint32_t* scan_totals;  // one per block

  template <class F>
  __device__ void each(std::size_t n, const F& f) const {
    const std::size_t stride = static_cast<std::size_t>(blockDim.x) * gridDim.x;
    for (std::size_t i = static_cast<std::size_t>(blockIdx.x) * blockDim.x + threadIdx.x; i < n; i += stride) f(i);
  }
  __device__ void sync() const { Barrier::sync(); }
  template <class F, class Op>
  __device__ void reduce(std::size_t n, const F& f, T init, Op op, T* out) const {
    using Reduce = cub::BlockReduce<T, persistent_block_size>;
    __shared__ typename Reduce::TempStorage temp;
    T s = init;
    each(n, [&](std::size_t i) { s = op(s, f(i)); });
    const T block = Reduce(temp).Reduce(s, op);
    if (threadIdx.x == 0) partials[blockIdx.x] = block;
    sync();
    if (blockIdx.x == 0) {  // its thread 0 is index 0 of the next each()
      T t = init;
      for (unsigned k = threadIdx.x; k < gridDim.x; k += blockDim.x) t = op(t, partials[k]);
      const T total = Reduce(temp).Reduce(t, op);
      if (threadIdx.x == 0) *out = total;
    }
  }
  template <class F>
  __device__ void sum(std::size_t n, const F& f, T* out) const {
    reduce(n, f, T(0), PlusOp{}, out);
  }
  __device__ void scan(const std::uint32_t* in, std::uint32_t* out, std::size_t n) const {
    using Scan = cub::BlockScan<std::uint32_t, persistent_block_size>;
    using Sum = cub::BlockReduce<std::uint32_t, persistent_block_size>;
    __shared__ typename Scan::TempStorage scan_temp;
    __shared__ typename Sum::TempStorage sum_temp;
    const std::size_t share = (n + gridDim.x - 1) / gridDim.x;
    const std::size_t lo = blockIdx.x * share < n ? blockIdx.x * share : n, hi = lo + share < n ? lo + share : n;
    std::uint32_t running = 0;
    for (std::size_t base = lo; base < hi; base += blockDim.x) {  // the same trips for the whole block
      const std::size_t i = base + threadIdx.x;
      std::uint32_t x = i < hi ? in[i] : 0u, total = 0;
      Scan(scan_temp).InclusiveSum(x, x, total);
      if (i < hi) out[i] = running + x;
      running += total;
      __syncthreads();  // scan_temp is reused
    }
    if (threadIdx.x == 0) scan_totals[blockIdx.x] = running;
    sync();
    std::uint32_t before = 0;
    for (unsigned k = threadIdx.x; k < blockIdx.x; k += blockDim.x) before += scan_totals[k];
    before = Sum(sum_temp).Sum(before);
    __shared__ std::uint32_t offset;
    if (threadIdx.x == 0) offset = before;
    __syncthreads();
    for (std::size_t i = lo + threadIdx.x; i < hi; i += blockDim.x) out[i] += offset;
  }
};

template <class Barrier, class Start, class Program, class T>
__global__ void __launch_bounds__(persistent_block_size)
    persistent_iterations_kernel(Start start, Program program, std::size_t count, T* partials,
                                 std::uint32_t* scan_totals) {
  const GridExec<T, Barrier> e{partials, scan_totals};
  start(e);
  for (std::size_t k = 1; k <= count; ++k) program(e, k, k == count);
}
#endif

// What a checked solve (persistent_checked_kernel) leaves, written by one
// thread at the kernel's end into memory the host reads (pinned): the last
// attempt's rule after its last check (the verdict: ConvergenceRule's
// iterations and status) and its number of checks, whose residuals are in the
// history in order; the retries and the iterations of every attempt.
template <class Rule>
struct CheckedRun {
  Rule rule;
  std::size_t checks, retries, total_iterations;
};

// The retries of a checked solve: an attempt whose rule ends diverged, while
// fewer than `max` retries were made, multiplies *scale by `factor` (one
// thread, visible to the start program after its first barrier) and starts
// the next attempt. *scale is 1 when the kernel starts, and again when it ends.
template <class T>
struct RetryRule {
  T factor;
  std::size_t max;
  T* scale;
};

#if GPUSOLVE_HAS_NVCC
// Attempts, each start(e, retry) (retry: false for the first) and runs of
// iterations up to each check of `rule` (next_check, stop(it, residual),
// diverged(): ConvergenceRule), each run's last iteration reducing the
// residual into *residual, `between` (a program ending in e.sync()) after a
// check that does not stop; an attempt that diverged starts again
// (RetryRule). Each block's first thread applies the rules to the reduced
// residual, the same in every block, so the grid takes every branch together.
// The rules' state lives in shared memory: in registers it would be live
// across every phase of the iterations. The start program is called from one
// place, so the kernel holds its code once. Where *hold is not 0 (a held
// step, World::advance_unattended) the kernel does nothing: every block reads
// the same word, written before the launch.
template <class Barrier, class Start, class Program, class Between, class Rule, class T>
__global__ void __launch_bounds__(persistent_block_size)
    persistent_checked_kernel(Start start, Program program, Between between, Rule rule,
                              RetryRule<T> retries, const T* residual, CheckedRun<Rule>* record, T* history,
                              const std::uint32_t* hold, T* partials, std::uint32_t* scan_totals) {
  static_assert(std::is_trivially_default_constructible_v<CheckedRun<Rule>>);
  if (hold != nullptr && *hold != 0) return;
  const GridExec<T, Barrier> e{partials, scan_totals};
  __shared__ CheckedRun<Rule> run;
  __shared__ bool stop, again;  // two flags: a thread may still read one while the first thread writes the other
  const bool first_thread = threadIdx.x == 0, writer = first_thread && blockIdx.x == 0;
  if (first_thread) run = CheckedRun<Rule>{rule, 0, 0, 0};
  __syncthreads();
  for (bool retry = false;; retry = true) {
    start(e, retry);
    for (std::size_t first = 1;;) {
      const std::size_t last = run.rule.next_check(first);  // its schedule may follow the checks taken
      for (std::size_t k = first; k <= last; ++k) program(e, k - first + 1, k == last);
      if (first_thread) {
        const T r = *residual;  // rewritten only after the next run's first barrier
        if (writer) history[run.checks] = r;
        ++run.checks;
        stop = run.rule.stop(last, r);
      }
      __syncthreads();
      if (stop) break;
      between(e);
      first = last + 1;
    }
    if (first_thread) {
      run.total_iterations += run.rule.iterations;
      again = run.rule.diverged() && run.retries < retries.max;
      if (again) {
        ++run.retries;
        run.rule = rule, run.checks = 0;
        if (writer) *retries.scale *= retries.factor;
      }
    }
    __syncthreads();
    if (!again) break;
  }
  if (writer) {  // no phase reads the scale after the last attempt's start
    *record = run;
    *retries.scale = T(1);
  }
}
#endif

// The start program of a run that starts nothing.
struct NoStart {
  template <class E>
  GPUSOLVE_HD void operator()(const E&) const {}
};

// run(start, program, count, width, stream) queues `start` and `count`
// iterations of `program` (the last one called with last = true) as one
// kernel of at most one block per `persistent_block_size` indices of `width`
// (the longest phase) and no more blocks than the GPU holds at once: one
// thread-block cluster where they fit in one, else a cooperative launch.
// GPU only: available() says whether it can run here (nvcc and a device with
// cooperative launch).
template <class Device, class T>
class PersistentLoop {
 public:
  static bool available() {
    if constexpr (std::is_same_v<Device, device::gpu> && GPUSOLVE_HAS_NVCC) {
      return gpusolve::detail::per_device([](int dev) {
               int coop = 0;
               GPUSOLVE_CUDA_CHECK(cudaDeviceGetAttribute(&coop, cudaDevAttrCooperativeLaunch, dev));
               return coop != 0 ? 1 : 0;
             }) != 0;
    } else {
      return false;
    }
  }

  template <class Start, class Program>
  void run(const Start& start, const Program& program, std::size_t count, std::size_t width, stream_t stream) {
#if GPUSOLVE_HAS_NVCC
    if constexpr (std::is_same_v<Device, device::gpu>) {
      T* partials = nullptr;
      std::uint32_t* scan_totals = nullptr;
      void* args[] = {const_cast<Start*>(&start), const_cast<Program*>(&program), &count, &partials, &scan_totals};
      launch_persistent(&persistent_iterations_kernel<GridBarrier, Start, Program, T>,
                        &persistent_iterations_kernel<ClusterBarrier, Start, Program, T>, width, args, partials,
                        scan_totals, stream);
      return;
    }
#endif
    (void)start, (void)program, (void)count, (void)width, (void)stream;
    unavailable();
  }

  // Queues a whole solve as one cooperative kernel (persistent_checked_kernel):
  // attempts of `start` and of `program` between the checks of `rule`, and
  // `retries`: neither the checks nor a retry needs the host.
  // Its verdict goes to *record and the residuals of the last attempt's checks
  // to history[0, record->checks): memory the host can read (pinned) once the
  // stream is done, without a copy; history holds rule.max_checks(). Nothing
  // runs, and nothing is written, where `hold` is set and *hold is not 0.
  template <class Start, class Program, class Between, class Rule>
  void run_checked(const Start& start, const Program& program, const Between& between, const Rule& rule,
                   const RetryRule<T>& retries, const T* residual, CheckedRun<Rule>* record, T* history,
                   std::size_t width, stream_t stream, const std::uint32_t* hold = nullptr) {
#if GPUSOLVE_HAS_NVCC
    if constexpr (std::is_same_v<Device, device::gpu>) {
      T* partials = nullptr;
      std::uint32_t* scan_totals = nullptr;
      void* args[] = {const_cast<Start*>(&start),    const_cast<Program*>(&program),
                      const_cast<Between*>(&between), const_cast<Rule*>(&rule),
                      const_cast<RetryRule<T>*>(&retries), const_cast<T**>(&residual),
                      &record,                        &history,
                      &hold,                          &partials,
                      &scan_totals};
      launch_persistent(&persistent_checked_kernel<GridBarrier, Start, Program, Between, Rule, T>,
                        &persistent_checked_kernel<ClusterBarrier, Start, Program, Between, Rule, T>, width, args,
                        partials, scan_totals, stream);
      return;
    }
#endif
    (void)start, (void)program, (void)between, (void)rule, (void)retries, (void)residual, (void)record, (void)history,
        (void)width, (void)stream, (void)hold;
    unavailable();
  }

  // Whether a grid that fits in one thread-block cluster is launched as one
  // (ClusterBarrier; on by default) or cooperatively like a larger grid.
  void set_clusters(bool on) { clusters_ = on; }
  // The grid of the last run, in blocks of persistent_block_size threads, and
  // whether it ran as one cluster.
  std::size_t blocks() const { return blocks_; }
  bool clustered() const { return clustered_; }

 private:
  [[noreturn]] static void unavailable() {
    throw UnsupportedError("gpusolve: the persistent solver kernel needs device::gpu and nvcc");
  }

#if GPUSOLVE_HAS_NVCC
  // Launches the persistent kernel on at most one block per
  // persistent_block_size indices of `width` and no more blocks than the GPU
  // holds at once: as one thread-block cluster (`clustered`, ClusterBarrier)
  // where that many blocks fit in one, else cooperatively (`grid`,
  // GridBarrier). Its arguments `args` end with the per-block scratch, whose
  // pointers `partials` and `scan_totals` are set here.
  template <class GridKernel, class ClusterKernel>
  void launch_persistent(GridKernel* grid, ClusterKernel* clustered, std::size_t width, void** args, T*& partials,
                         std::uint32_t*& scan_totals, stream_t stream) {
    const int per_sm = gpusolve::detail::per_device([grid](int) {
      int blocks = 0;
      GPUSOLVE_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&blocks, grid, persistent_block_size, 0));
      return blocks;
    });
    const std::size_t cluster_max =
        std::size_t(gpusolve::detail::per_device([clustered](int dev) { return largest_cluster(clustered, dev); }));
    if (per_sm == 0)
      throw UnsupportedError("gpusolve: the persistent solver kernel does not fit on one multiprocessor");
    const std::size_t wanted = (width + persistent_block_size - 1) / persistent_block_size;
    const std::size_t resident =
        static_cast<std::size_t>(per_sm) * static_cast<std::size_t>(gpusolve::detail::sm_count());
    const std::size_t blocks = wanted == 0 ? 1 : (wanted < resident ? wanted : resident);
    blocks_ = blocks;
    clustered_ = clusters_ && blocks <= cluster_max;
    if (partials_.size_x() < blocks) partials_.resize(blocks);
    if (scan_totals_.size_x() < blocks) scan_totals_.resize(blocks);
    partials = partials_.data();
    scan_totals = scan_totals_.data();
    if (!clustered_) {
      GPUSOLVE_CUDA_CHECK(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(grid), dim3(unsigned(blocks)),
                                                      dim3(persistent_block_size), args, 0, stream));
      return;
    }
    cudaLaunchAttribute cluster{};
    cluster.id = cudaLaunchAttributeClusterDimension;
    cluster.val.clusterDim.x = unsigned(blocks), cluster.val.clusterDim.y = 1, cluster.val.clusterDim.z = 1;
    cudaLaunchConfig_t config{};
    config.gridDim = dim3(unsigned(blocks)), config.blockDim = dim3(persistent_block_size), config.stream = stream;
    config.attrs = &cluster, config.numAttrs = 1;
    GPUSOLVE_CUDA_CHECK(cudaLaunchKernelExC(&config, reinterpret_cast<const void*>(clustered), args));
  }

  // The most blocks of `kernel` that run as one cluster here: 0 where none
  // can (a device before sm_90, or the kernel's binary built for one).
  template <class Kernel>
  static int largest_cluster(Kernel* kernel, int dev) {
    int supported = 0;
    GPUSOLVE_CUDA_CHECK(cudaDeviceGetAttribute(&supported, cudaDevAttrClusterLaunch, dev));
    cudaFuncAttributes attributes{};
    GPUSOLVE_CUDA_CHECK(cudaFuncGetAttributes(&attributes, reinterpret_cast<const void*>(kernel)));
    if (!supported || attributes.binaryVersion < 90) return 0;
    GPUSOLVE_CUDA_CHECK(cudaFuncSetAttribute(reinterpret_cast<const void*>(kernel),
                                             cudaFuncAttributeNonPortableClusterSizeAllowed, 1));
    cudaLaunchConfig_t config{};
    config.gridDim = dim3(persistent_max_cluster), config.blockDim = dim3(persistent_block_size);
    int size = 0;
    GPUSOLVE_CUDA_CHECK(cudaOccupancyMaxPotentialClusterSize(&size, reinterpret_cast<const void*>(kernel), &config));
    return size < int(persistent_max_cluster) ? size : int(persistent_max_cluster);
  }
#endif

  std::size_t blocks_ = 0;
  bool clusters_ = true, clustered_ = false;
  VectorD1<T, device_is<Device>> partials_;
  VectorD1<std::uint32_t, device_is<Device>> scan_totals_;
};

}  // namespace gpusolve::rbd::detail
