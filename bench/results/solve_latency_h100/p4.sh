#!/usr/bin/env bash
# lean: suite at the new head; ncu SASS profile of the stack's solve kernel; the sphere pile new vs head_atlas; the pyramid's solve
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
for f in head_atlas new_atlas gpusolve_gpu_tests; do gunzip -c $f.gz > $B/$f; chmod +x $B/$f; done
O=$OUT/p4; mkdir -p $O
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
$B/gpusolve_gpu_tests > $O/suite.log 2>&1; echo "suite rc=$? ($SECONDS s): $(grep -E 'All tests passed|test cases' $O/suite.log | tail -1)"
prof() {  # name, ncu filter args..., -- atlas args
  local name=$1; shift; local f=(); while [ "$1" != "--" ]; do f+=("$1"); shift; done; shift
  timeout 60 ncu --cache-control none --clock-control none --set full --import-source no "${f[@]}" -o $O/$name $B/new_atlas "$@" > $O/$name.log 2>&1
  echo "ncu $name rc=$? ($SECONDS s)"
  ncu -i $O/$name.ncu-rep --page source --csv --print-source sass > $O/${name}_sass.csv 2> /dev/null
  ncu -i $O/$name.ncu-rep --page details --csv > $O/${name}_details.csv 2> /dev/null
  rm -f $O/$name.ncu-rep
  cd $OUT && tar czf p4.tgz p4; cd - > /dev/null
}
prof stack_solve --kernel-name regex:persistent --launch-skip 600 --launch-count 1 -- --scene stack --methods apgd --budgets default --steps 800
for v in head_atlas new_atlas; do
  $B/$v --scene pile --n 10000 --methods apgd --budgets default --phases --csv $O/pile_${v}.csv > $O/pile_${v}.log 2>&1
  echo "pile $v ($SECONDS s): $(grep -oE 'median [0-9.]+\)|penetration [0-9.]+%|detection [0-9.]+ ms' $O/pile_${v}.log | tr '\n' ' ')"
  cd $OUT && tar czf p4.tgz p4; cd - > /dev/null
done
prof pyramid_solve --kernel-name regex:persistent --launch-skip 600 --launch-count 1 -- --scene pyramid --methods apgd --budgets default --steps 800
cd $OUT && tar czf p4.tgz p4 && rm -rf p4
