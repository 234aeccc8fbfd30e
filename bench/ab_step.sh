#!/usr/bin/env bash
# Two builds side by side on one GPU, interleaved (base, new; then new, base):
# the whole step at 1 000 to 1 000 000 spheres (Jacobi 10 and the defaults) and
# the shared pile at the defaults (PILE.md's 10 000 and 100 000 spheres).
# Usage: bench/ab_step.sh BASE_BIN_DIR NEW_BIN_DIR OUT_DIR
# Each BIN_DIR holds gpusolve_bench_step and gpusolve_bench_atlas of one build.
set -euo pipefail
base="$1" new="$2" out="$3"
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$out/gpu.txt"
step=(--n 1000,10000,100000,1000000 --modes jacobi10,defaults --settle 600 --steps 100 --cpu-max 0)
pile=(--scene pile --n 10000,100000 --methods apgd --budgets default)
run() {  # build label, round
  local dir="$base"; [ "$1" = new ] && dir="$new"
  echo "== $1, round $2 ($SECONDS s)"
  "$dir/gpusolve_bench_step" "${step[@]}" --csv "$out/step_$1_round$2.csv" > "$out/step_$1_round$2.log" 2>&1
  "$dir/gpusolve_bench_atlas" "${pile[@]}" --csv "$out/pile_$1_round$2.csv" > "$out/pile_$1_round$2.log" 2>&1
}
run base 1; run new 1
run new 2; run base 2
echo "done ($SECONDS s)"
