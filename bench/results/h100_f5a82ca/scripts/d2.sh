#!/usr/bin/env bash
# issue 39: the distributed GPU tests at 1 and 2 ranks; the 100 000-sphere pile at 1 and 2 ranks sharing the GPU
# with the skin (82883b8), without and with the CUDA MPS daemon; skin 0 for the before row
set -uo pipefail
cd "$(dirname "$0")"; B=$PWD/bin; mkdir -p $B
for f in gpusolve_bench_distributed gpusolve_distributed_gpu_tests; do gunzip -c $f.gz > $B/$f; chmod +x $B/$f; done
cd ..
O=$OUT/d; mkdir -p $O
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | tee $O/gpu.txt
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export LD_LIBRARY_PATH=$(python3 -c "import nvidia.nccl, os; print(os.path.dirname(nvidia.nccl.__file__))" 2>/dev/null)/lib:${LD_LIBRARY_PATH:-}
for r in 1 2; do timeout 150 mpirun -np $r $B/gpusolve_distributed_gpu_tests "[distributed]" > $O/tests_$r.log 2>&1; echo "tests $r ranks rc=$? ($SECONDS s): $(grep -E 'All tests|test cases' $O/tests_$r.log | tail -1)"; done
D=$B/gpusolve_bench_distributed
for r in 1 2; do timeout 100 mpirun -np $r $D --backend gpu --n 100000 --steps 300 --csv $O/gpu_skin.csv 2>&1 | tail -1; done
timeout 100 mpirun -np 2 $D --backend gpu --n 100000 --steps 300 --skin 0 --csv $O/gpu_skin.csv 2>&1 | tail -1
export CUDA_MPS_PIPE_DIRECTORY=/tmp/mps_pipe CUDA_MPS_LOG_DIRECTORY=/tmp/mps_log; mkdir -p $CUDA_MPS_PIPE_DIRECTORY $CUDA_MPS_LOG_DIRECTORY
nvidia-cuda-mps-control -d && echo "MPS on"
for r in 1 2; do timeout 100 mpirun -np $r -x CUDA_MPS_PIPE_DIRECTORY -x CUDA_MPS_LOG_DIRECTORY $D --backend gpu --n 100000 --steps 300 --csv $O/gpu_skin_mps.csv 2>&1 | tail -1; done
echo quit | nvidia-cuda-mps-control
echo "done ($SECONDS s)"
cd $OUT && tar czf d.tgz d && rm -rf d
