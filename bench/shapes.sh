#!/usr/bin/env bash
# The atlas's rows of every shape on one GPU: the shared cube pile (PILE.md,
# 10 000 cubes) and the mixed pile (spheres, boxes, capsules, clumps) at the
# defaults and at fixed budgets, and the stability rows of a 20-layer box
# pyramid (210 boxes), a stack of 20 boxes, a field of 20 such pyramids and a
# tower of 100 slabs for 10 s at dt 0.0025 per method.
# Usage: bench/shapes.sh BIN_DIR OUT_DIR   (BIN_DIR holds gpusolve_bench_atlas)
set -euo pipefail
bin="$1/gpusolve_bench_atlas" out="$2"
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee "$out/gpu.txt"
"$bin" --scene cubes --methods apgd,jacobi --budgets default,it20 --csv "$out/cubes.csv" > "$out/cubes.log" 2>&1
"$bin" --scene mixed --methods apgd,jacobi --budgets default,it20 --csv "$out/mixed.csv" > "$out/mixed.log" 2>&1
for scene in pyramid stack; do
  "$bin" --scene "$scene" --methods apgd,jacobi,gauss-seidel,substepping --budgets default \
    --csv "$out/$scene.csv" > "$out/$scene.log" 2>&1
done
# The 20-pyramid field (4 200 boxes) and the tower of 100 slabs, 10 s each.
for scene in field slabs; do
  "$bin" --scene "$scene" --methods apgd,jacobi,substepping --budgets default \
    --csv "$out/$scene.csv" > "$out/$scene.log" 2>&1
done
grep -h -E '^    ' "$out"/cubes.log "$out"/mixed.log "$out"/pyramid.log "$out"/stack.log "$out"/field.log "$out"/slabs.log
echo "done ($SECONDS s)"
