#!/usr/bin/env bash
# Installs what building and testing gpusolve needs on a fresh Debian/Ubuntu
# machine: CMake, a C++ compiler, Catch2, OpenMPI and Python 3 from the
# distribution.
# The CUDA toolkit (nvcc, CCCL) is expected to be installed already; without it
# only the host-compiler parts build.
set -euo pipefail

need=()
command -v cmake >/dev/null 2>&1 || need+=(cmake)
command -v g++ >/dev/null 2>&1 || need+=(g++)
command -v python3 >/dev/null 2>&1 || need+=(python3)
[ -f /usr/include/catch2/catch.hpp ] || [ -f /usr/include/catch2/catch_all.hpp ] || need+=(catch2)
# MPI for the distributed world's tests (mpirun at 1, 2 and 4 ranks).
command -v mpicxx >/dev/null 2>&1 && command -v mpirun >/dev/null 2>&1 || need+=(libopenmpi-dev openmpi-bin)
[ -n "${GPUSOLVE_EXTRA_PACKAGES:-}" ] && need+=(${GPUSOLVE_EXTRA_PACKAGES})

if [ ${#need[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "install_deps: installing ${need[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}"
fi
# cuobjdump and nvdisasm (the SASS audit) are not part of every toolkit install;
# NVIDIA publishes them on PyPI. tools/audit.py finds them on this python's path.
if ! python3 -c "import sys; sys.path.insert(0, 'tools'); import audit; sys.exit(not audit.find_tool('cuobjdump'))"; then
  echo "install_deps: installing cuobjdump and nvdisasm from PyPI"
  python3 -m pip install --quiet --disable-pip-version-check \
    nvidia-cuda-cuobjdump==13.2.86 nvidia-cuda-nvdisasm==13.2.86
fi
if ! command -v nvcc >/dev/null 2>&1 && [ -x /usr/local/cuda/bin/nvcc ]; then
  echo "install_deps: nvcc is at /usr/local/cuda/bin; add it to PATH to build the CUDA targets"
fi
