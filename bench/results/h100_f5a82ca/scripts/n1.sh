#!/usr/bin/env bash
# next lease, first call: the GPU suite at the head; the coloured Gauss-Seidel after the revert (head) against 353d3fa (fin)
# and d651295 (gsp); the step bench on the cube and sphere piles before (4cf0ec0) and after the zeroed detection key (head):
# step (host waits), queued, unattended; and the head (the box slabs, the walk's batches, the clip's turns)
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
for f in gpusolve_gpu_tests head_atlas fin_atlas gsp_atlas step_4cf0ec0 step_352d606 step_head; do gunzip -c $f.gz > $B/$f; chmod +x $B/$f; done
O=$OUT/n; mkdir -p $O
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
$B/gpusolve_gpu_tests > $O/suite.log 2>&1; echo "suite rc=$? ($SECONDS s): $(tail -2 $O/suite.log | head -1)"
for round in 1 2; do for v in gsp fin head; do
  $B/${v}_atlas --scene pyramid --methods gauss-seidel --budgets default --phases --csv $O/gs_pyr_${v}_$round.csv > $O/gs_pyr_${v}_$round.log 2>&1
  $B/${v}_atlas --scene stack --methods gauss-seidel --budgets default --csv $O/gs_stack_${v}_$round.csv > $O/gs_stack_${v}_$round.log 2>&1
  echo "GS $v $round ($SECONDS s): $(grep -o 'median [0-9.]*' $O/gs_pyr_${v}_$round.log | head -1) / $(grep -o 'median [0-9.]*' $O/gs_stack_${v}_$round.log | head -1)"
done; done
for round in 1 2; do for v in 4cf0ec0 352d606 head; do
  $B/step_$v --scene cubes --n 10000 --settle 1500 --steps 100 --modes jacobi10,defaults --cpu-max 0 --csv $O/step_cubes_${v}_$round.csv > $O/step_cubes_${v}_$round.log 2>&1
  $B/step_$v --scene pile --n 10000 --settle 900 --steps 100 --modes jacobi10,defaults --cpu-max 0 --csv $O/step_pile_${v}_$round.csv > $O/step_pile_${v}_$round.log 2>&1
  echo "step $v $round ($SECONDS s)"; grep -hE "^    gpu" $O/step_cubes_${v}_$round.log $O/step_pile_${v}_$round.log | cut -c1-200
done; done
cd $OUT && tar czf n.tgz n && rm -rf n
