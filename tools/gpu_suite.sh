#!/usr/bin/env bash
# The whole GPU check in one command, for a machine with a CUDA GPU: builds the
# sm_90 preset, runs ctest (host and GPU suites, consumers, audit), then the GPU
# suite under compute-sanitizer memcheck and initcheck (reads of device memory
# never written), and racecheck (shared-memory hazards) over the tests that run
# the step's CUB sorts, scans, selections and reductions and the persistent
# solver kernel's block reductions (the whole suite under
# racecheck takes longer than ten minutes; the graph replay test too). Logs go
# to $OUT (or ./out/gpu).
# API errors are not reported by the sanitizer because the error-path tests
# provoke them on purpose; memory errors are.
# SANITIZERS: the tools to run, in order (default "memcheck initcheck racecheck";
# "" for none): the suite and all three take longer than one ten-minute call on
# the lent machine, so a call can take the suite and memcheck, the next the rest.
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/gpu}"; mkdir -p "$out"
extra=()
[ -n "${GPUSOLVE_CATCH2_INCLUDE_DIR:-}" ] && extra+=("-DGPUSOLVE_CATCH2_INCLUDE_DIR=$GPUSOLVE_CATCH2_INCLUDE_DIR")
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$out/gpu.txt"
# GPUSOLVE_GPU_TESTS_BIN: a GPU suite built elsewhere for this GPU (carried to a
# lent machine); then only that suite and its sanitizer runs, not the build and ctest.
tests="${GPUSOLVE_GPU_TESTS_BIN:-build/gpu/tests/gpusolve_gpu_tests}"
if [ -n "${GPUSOLVE_GPU_TESTS_BIN:-}" ]; then
  "$tests" 2>&1 | tee "$out/suite.log" | tail -4
  rc=${PIPESTATUS[0]}
else
  cmake --preset gpu "${extra[@]}" > "$out/configure.log" 2>&1 || { tail -30 "$out/configure.log"; exit 1; }
  cmake --build --preset gpu -j "$(nproc)" > "$out/build.log" 2>&1 || { grep -E "error|Error" "$out/build.log" | head -40; exit 1; }
  ctest --preset gpu 2>&1 | tee "$out/ctest.log" | tail -15
  rc=${PIPESTATUS[0]}
fi
status=0
for tool in ${SANITIZERS-memcheck initcheck racecheck}; do
  spec=()
  [ "$tool" = racecheck ] && spec=("[rbd_step]~[graphs],[collision],[rbd_persistent]")
  compute-sanitizer --tool "$tool" --report-api-errors no --error-exitcode 9 \
    "$tests" "${spec[@]}" > "$out/$tool.log" 2>&1
  rc_tool=$?
  echo "$tool ($SECONDS s since the start): $(grep -E "ERROR SUMMARY|RACECHECK SUMMARY" "$out/$tool.log" | tail -1) (rc=$rc_tool)"
  grep -E "^(All tests passed|test cases)" "$out/$tool.log" | tail -1
  [ "$rc_tool" -eq 0 ] || status=1
done
echo "ctest rc=$rc sanitizers $([ $status -eq 0 ] && echo clean || echo FAILED)"
[ "$rc" -eq 0 ] && [ "$status" -eq 0 ]
