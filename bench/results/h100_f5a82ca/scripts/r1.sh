#!/usr/bin/env bash
# racecheck over the GPU suite's files it did not reach on 2026-12-07 (each file a run, 110 s each)
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
[ -x $B/gpusolve_gpu_tests ] || { gunzip -c gpusolve_gpu_tests.gz > $B/gpusolve_gpu_tests; chmod +x $B/gpusolve_gpu_tests; }
O=$OUT/r; mkdir -p $O
for f in test_rbd_reorder test_rbd_shapes test_rbd_solver test_rbd_step_pipeline test_rbd_unattended; do
  timeout 110 compute-sanitizer --tool racecheck --report-api-errors no --error-exitcode 9 $B/gpusolve_gpu_tests -# "[#$f]" > $O/$f.log 2>&1
  echo "$f rc=$? ($SECONDS s): $(grep -E 'RACECHECK SUMMARY' $O/$f.log | tail -1) / $(grep -E 'All tests passed|test cases' $O/$f.log | tail -1)"
done
cd $OUT && tar czf r.tgz r && rm -rf r
