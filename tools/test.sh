#!/usr/bin/env bash
# The test command of the README: installs what it needs, builds everything
# (CUDA targets too when nvcc is present), runs the whole suite, then runs the
# host suite once more under AddressSanitizer and UndefinedBehaviorSanitizer.
# Fails when anything fails. Without a GPU the GPU suite is reported as skipped.
set -euo pipefail
cd "$(dirname "$0")/.."

[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
bash tools/install_deps.sh
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)}"

cmake --workflow --preset default
cmake --workflow --preset sanitize
