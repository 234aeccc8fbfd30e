#!/usr/bin/env bash
# Build times (docs/build_time.md): the README's World program
# (examples/readme/readme_world.cu) compiled by nvcc as one translation unit,
# `runs` times, with nvcc's time per phase; then, with --suite, configure plus
# build of the GPU suite and the atlas and step benches (the `gpu` preset) in
# a fresh build folder with `jobs` parallel jobs.
# Usage: bench/build_time.sh OUT_DIR [runs=3] [jobs=nproc] [--suite]
# Writes OUT_DIR/readme_runs.csv (seconds per run), readme_phases.csv (nvcc
# --time of the last run) and, with --suite, suite.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
out="$1" runs="${2:-3}" jobs="${3:-$(nproc)}" suite="${4:-}"
mkdir -p "$out"
secs() { printf "%d.%01d" $((($2 - $1) / 1000000000)) $((($2 - $1) / 100000000 % 10)); }  # from two date +%s%N
[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
flags=(-std=c++17 -O3 -DNDEBUG --extended-lambda --expt-relaxed-constexpr -arch=sm_90 -Iinclude)
echo "run,seconds,cores" > "$out/readme_runs.csv"
for r in $(seq 1 "$runs"); do
  rm -f "$out/readme_phases.csv"
  start=$(date +%s%N)
  nvcc "${flags[@]}" --time "$out/readme_phases.csv" -c examples/readme/readme_world.cu -o "$out/readme_world.o"
  end=$(date +%s%N)
  echo "$r,$(secs "$start" "$end"),$(nproc)" >> "$out/readme_runs.csv"
done
rm -f "$out/readme_world.o"
echo "README program, seconds per run on $(nproc) cores:"; tail -n +2 "$out/readme_runs.csv" | cut -d, -f2 | sort -n | tr '\n' ' '; echo
cut -d, -f2,7 "$out/readme_phases.csv"
if [ "$suite" = --suite ]; then
  dir=$(mktemp -d)
  start=$(date +%s%N)
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
    -DGPUSOLVE_BUILD_EXAMPLES=OFF ${GPUSOLVE_CATCH2_INCLUDE_DIR:+-DGPUSOLVE_CATCH2_INCLUDE_DIR=$GPUSOLVE_CATCH2_INCLUDE_DIR} > "$out/suite_configure.log"
  mid=$(date +%s%N)
  cmake --build "$dir" -j "$jobs" --target gpusolve_gpu_tests gpusolve_bench_atlas gpusolve_bench_step > "$out/suite_build.log"
  end=$(date +%s%N)
  echo "configure $(secs "$start" "$mid") s, build $(secs "$mid" "$end") s, total $(secs "$start" "$end") s" \
    "($jobs jobs, $(nproc) cores)" | tee "$out/suite.txt"
  echo "$dir" > "$out/suite_dir.txt"
fi
