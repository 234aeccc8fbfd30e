#!/usr/bin/env bash
# issue 35: detection after the box slabs (61ce6a6), batches in every walk (315bf42), and at the head (batches in a box's
# candidate walk only, the clip polygons' turns), against 352d606:
# the atlas's pyramid, stack, cube pile (defaults, it10), mixed pile and sphere pile, --phases, two rounds, alternating
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
for f in atlas_352d606 atlas_61ce6a6 atlas_315bf42 head_atlas; do gunzip -c $f.gz > $B/$f; chmod +x $B/$f; done
O=$OUT/a1; mkdir -p $O
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
for round in 1 2; do for v in atlas_352d606 atlas_61ce6a6 atlas_315bf42 head_atlas; do
  for sc in pyramid stack; do $B/$v --scene $sc --methods apgd --budgets default --phases --csv $O/${sc}_${v}_$round.csv > $O/${sc}_${v}_$round.log 2>&1; done
  $B/$v --scene cubes --n 10000 --methods apgd --budgets default,it10 --phases --csv $O/cubes_${v}_$round.csv > $O/cubes_${v}_$round.log 2>&1
  $B/$v --scene mixed --n 10000 --methods apgd --budgets default --phases --csv $O/mixed_${v}_$round.csv > $O/mixed_${v}_$round.log 2>&1
  $B/$v --scene pile --n 10000 --methods apgd --budgets default --phases --csv $O/pile_${v}_$round.csv > $O/pile_${v}_$round.log 2>&1
  echo "== $v round $round ($SECONDS s)"
  for sc in pyramid stack cubes mixed pile; do grep -hE "^\.\.\.|ms/step|phases" $O/${sc}_${v}_$round.log | sed 's/ margin=0.1 warm 0.8 dt=0.0025//' | cut -c1-160; done
done; done
cd $OUT && tar czf a1.tgz a1 && rm -rf a1
