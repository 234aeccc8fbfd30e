start=$(date +%s)
el() { echo "[t=$(( $(date +%s) - start ))s] $*"; }
bash tools/gpu_suite.sh 2>&1 | grep -vE "^ +Start|Test +#" | tail -12
el suite
B=build/gpu
timeout 40 $B/examples/gpusolve_scenes_gpu --scene hopper --backend gpu --steps 10000 --status-every 2500 --frames none 2>&1 | tail -3
el hopper
timeout 120 $B/bench/gpusolve_bench_step --n 300000,600000 --modes defaults --loop persistent,launches --settle 300 --steps 30 --cpu-max 0 --csv $OUT/crossover.csv > $OUT/crossover.log 2>&1; grep -E "^    gpu" $OUT/crossover.log
el crossover
timeout 40 $B/bench/gpusolve_bench_step --n 10000 --modes jacobi10,defaults --loop auto --settle 600 --steps 60 --cpu-max 0 2>&1 | grep -E "^    gpu"
el auto
