#!/usr/bin/env bash
# sanitizers on the GPU suite (memcheck, initcheck, racecheck) and ncu of a 1M pile (issue 38)
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
for f in gpusolve_gpu_tests; do gunzip -c $f.gz > $B/$f; chmod +x $B/$f; done
cd ..
O=$OUT/s; mkdir -p $O
for t in memcheck initcheck racecheck; do
  timeout 170 compute-sanitizer --tool $t --report-api-errors no --error-exitcode 9 $B/gpusolve_gpu_tests > $O/$t.log 2>&1; echo "$t rc=$? ($SECONDS s): $(grep -E 'ERROR SUMMARY|RACECHECK SUMMARY' $O/$t.log | tail -1) / $(grep -E 'All tests passed|test cases' $O/$t.log | tail -1)"
done
cd $OUT && tar czf s.tgz s && rm -rf s
