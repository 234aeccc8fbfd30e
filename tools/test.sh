#!/usr/bin/env bash
# The test command of the README: installs what it needs, builds what the tests
# need (the CUDA targets too when nvcc is present; the GPU suite where a GPU is
# usable), runs the whole suite, tests in parallel, and runs the host suite once
# more under AddressSanitizer and UndefinedBehaviorSanitizer.
# Fails when anything fails. Without a GPU the GPU suite is reported as skipped.
set -euo pipefail
cd "$(dirname "$0")/.."

[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
bash tools/install_deps.sh
jobs="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"
export CMAKE_BUILD_PARALLEL_LEVEL="$jobs"

# The GPU suite is built where it can run; tools/gpu_suite.sh builds it on a GPU machine.
gpu_tests=OFF
command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L >/dev/null 2>&1 && gpu_tests=ON
[ -n "${GPUSOLVE_BUILD_GPU_TESTS:-}" ] && gpu_tests="$GPUSOLVE_BUILD_GPU_TESTS"

# The prebuilt Worlds' GPU half (a minute of nvcc) likewise only where a GPU runs it.
cmake --preset default -DGPUSOLVE_BUILD_BENCH=OFF -DGPUSOLVE_BUILD_GPU_TESTS="$gpu_tests" -DGPUSOLVE_GPU_WORLDS="$gpu_tests"
cmake --build --preset default
ctest --preset default -j "$jobs"
cmake --preset sanitize
cmake --build --preset sanitize
ctest --preset sanitize -j "$jobs"
