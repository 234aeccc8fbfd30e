#!/usr/bin/env bash
# The atlas's rows of unions on one GPU (issue 36): the pile of 100 000
# three-sphere clumps against the shared pile of 300 000 spheres (the same
# spheres' worth of work), both for 4 000 steps (10 s: both settled), and the
# piles of 10 000 clumps and of 10 000 four-part unions, with their phases,
# at the defaults.
# Usage: bench/unions.sh BIN_DIR OUT_DIR   (BIN_DIR holds gpusolve_bench_atlas)
set -euo pipefail
bin="$1/gpusolve_bench_atlas" out="$2"
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$out/gpu.txt"
row() {
  local name="$1"
  shift
  "$bin" "$@" --methods apgd --budgets default --csv "$out/$name.csv" > "$out/$name.log" 2>&1
}
row clumps_100k --scene clumps --n 100000 --steps 4000
row pile_300k --scene pile --n 300000 --steps 4000
row clumps_10k --scene clumps --n 10000 --phases
row unions_10k --scene unions --n 10000 --phases
grep -h -E '^    ' "$out"/clumps_100k.log "$out"/pile_300k.log "$out"/clumps_10k.log "$out"/unions_10k.log
echo "done ($SECONDS s)"
