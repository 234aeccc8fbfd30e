#!/usr/bin/env bash
set -uo pipefail
R=$OUT/r; mkdir -p $R
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee $R/gpu.txt
B=.gpubin/new/gpusolve_gpu_tests
timeout 150 $B > $R/suite.log 2>&1; echo "suite rc=$? ($SECONDS s)"; grep -E '^(All tests passed|test cases|assertions)' $R/suite.log
grep -B5 -A15 FAILED $R/suite.log | head -80
timeout 120 bash bench/shapes.sh .gpubin/new $R/shapes; echo "shapes rc=$? ($SECONDS s)"
timeout 200 bash bench/ab_step.sh .gpubin/base .gpubin/new $R/ab > $R/ab.log 2>&1; echo "ab rc=$? ($SECONDS s)"
python3 bench/ab_table.py $R/ab 2>&1 | tail -25
for tool in memcheck initcheck; do
  timeout 110 compute-sanitizer --tool $tool --report-api-errors no --error-exitcode 9 $B > $R/$tool.log 2>&1
  echo "$tool rc=$? ($SECONDS s): $(grep -E 'ERROR SUMMARY' $R/$tool.log | tail -1)"; grep -E '^(All tests passed|test cases)' $R/$tool.log | tail -1
done
tar czf $OUT/results.tgz -C $R .
