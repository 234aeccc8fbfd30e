#!/usr/bin/env bash
# Build times (docs/build_time.md). The README's World program
# (examples/readme/readme_world.cu) compiled as one translation unit, `runs`
# times each way: by nvcc from the headers alone; by nvcc and by g++ against
# the prebuilt Worlds (gpusolve::worlds, prebuilt_worlds.hpp), whose own
# one-time compile is timed too, with nvcc's time per phase of every run
# (phases_*.csv, appended run after run). With --suite: configure plus build of the GPU suite and the
# atlas and step benches in a fresh build folder with `jobs` parallel jobs.
# Usage: bench/build_time.sh OUT_DIR [runs=3] [jobs=nproc] [--suite]
# Writes OUT_DIR/build_times.csv (way,run,seconds,cores), phases_*.csv and,
# with --suite, suite.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
out="$1" runs="${2:-3}" jobs="${3:-$(nproc)}" suite="${4:-}"
mkdir -p "$out"
secs() { printf "%d.%01d" $((($2 - $1) / 1000000000)) $((($2 - $1) / 100000000 % 10)); }  # from two date +%s%N
[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
cuda_inc="$(dirname "$(dirname "$(command -v nvcc)")")/include"
nvcc_flags=(-std=c++17 -O3 -DNDEBUG --extended-lambda --expt-relaxed-constexpr -arch=sm_90 -Iinclude)
gxx_flags=(-std=c++17 -O3 -DNDEBUG -Iinclude -I"$cuda_inc" -I"$cuda_inc/cccl")
prebuilt=(-DGPUSOLVE_PREBUILT_WORLDS -DGPUSOLVE_PREBUILT_GPU_WORLDS)
tmp=$(mktemp -d)
cp examples/readme/readme_world.cu "$tmp/readme_world.cpp"
echo "way,run,seconds,cores" > "$out/build_times.csv"
timed() {  # way run command...
  local way="$1" run="$2"; shift 2
  local start end; start=$(date +%s%N); "$@"; end=$(date +%s%N)
  echo "$way,$run,$(secs "$start" "$end"),$(nproc)" >> "$out/build_times.csv"
}
for r in $(seq 1 "$runs"); do
  timed nvcc_headers "$r" nvcc "${nvcc_flags[@]}" --time "$out/phases_nvcc_headers.csv" -c examples/readme/readme_world.cu -o "$tmp/a.o"
  timed nvcc_prebuilt "$r" nvcc "${nvcc_flags[@]}" "${prebuilt[@]}" --time "$out/phases_nvcc_prebuilt.csv" -c examples/readme/readme_world.cu -o "$tmp/b.o"
  timed gxx_prebuilt "$r" g++ "${gxx_flags[@]}" "${prebuilt[@]}" -c "$tmp/readme_world.cpp" -o "$tmp/c.o"
done
timed library_gpu 1 nvcc "${nvcc_flags[@]}" -c src/worlds_gpu.cu -o "$tmp/worlds_gpu.o"
timed library_cpu 1 g++ "${gxx_flags[@]}" -fopenmp -c src/worlds_cpu.cpp -o "$tmp/worlds_cpu.o"
rm -rf "$tmp"
echo "seconds on $(nproc) cores (way: runs):"
for way in nvcc_headers nvcc_prebuilt gxx_prebuilt library_gpu library_cpu; do
  echo "  $way: $(grep "^$way," "$out/build_times.csv" | cut -d, -f3 | sort -n | tr '\n' ' ')"
done
if [ "$suite" = --suite ]; then
  dir=$(mktemp -d)
  start=$(date +%s%N)
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CUDA_ARCHITECTURES=90 \
    ${GPUSOLVE_CATCH2_INCLUDE_DIR:+-DGPUSOLVE_CATCH2_INCLUDE_DIR=$GPUSOLVE_CATCH2_INCLUDE_DIR} > "$out/suite_configure.log"
  mid=$(date +%s%N)
  cmake --build "$dir" -j "$jobs" --target gpusolve_gpu_tests gpusolve_bench_atlas gpusolve_bench_step > "$out/suite_build.log"
  end=$(date +%s%N)
  echo "configure $(secs "$start" "$mid") s, build $(secs "$mid" "$end") s, total $(secs "$start" "$end") s" \
    "($jobs jobs, $(nproc) cores)" | tee "$out/suite.txt"
  echo "$dir" > "$out/suite_dir.txt"
fi
