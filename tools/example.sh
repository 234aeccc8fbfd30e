#!/usr/bin/env bash
# The README's main command: installs what it needs (povray included), builds
# gpusolve_scenes (its CUDA build where a GPU is usable), runs the well scene
# at a size that takes about a minute and the blocks scene (every shape),
# renders the last frame of each and says where everything is. Usage: tools/example.sh [extra gpusolve_scenes options]
set -euo pipefail
cd "$(dirname "$0")/.."

[ -x /usr/local/cuda/bin/nvcc ] && export PATH="/usr/local/cuda/bin:$PATH"
GPUSOLVE_EXTRA_PACKAGES=povray bash tools/install_deps.sh

# The CUDA build of the scenes where a GPU can run it; else the host compiler's
# build, the same code on the CPU backend (and no nvcc compile to wait for).
gpu=OFF
command -v nvcc >/dev/null 2>&1 && command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L >/dev/null 2>&1 && gpu=ON
cmake -S . -B build/example -DCMAKE_BUILD_TYPE=Release -DGPUSOLVE_ENABLE_CUDA=$gpu \
  -DGPUSOLVE_BUILD_TESTS=OFF -DGPUSOLVE_BUILD_BENCH=OFF >/dev/null
target=gpusolve_scenes
[ "$gpu" = ON ] && target=gpusolve_scenes_gpu
cmake --build build/example --target "$target" -j "$(nproc)"

# About a minute either way. On a GPU: 2 400 spheres over 12 000 steps (the
# thesis's full well, 3 900 over 20 000, took 102 s on an H100); on a CPU: 600
# spheres over 6 000 steps (15 s simulated; the last ones still falling), 35 to
# 60 s on 2 busy cores. The backend is auto: the GPU when there is one.
out=out/well
args=(--steps 6000 --scale 600 --frame-every 1500)
if [ "$gpu" = ON ]; then
  args=(--steps 12000 --scale 2400 --frame-every 3000)
fi
start=$(date +%s)
# A run that reports divergence still has outputs worth looking at: render and
# report them, then exit with the program's status.
status=0
"build/example/examples/$target" well --out "$out" "${args[@]}" "$@" || status=$?
echo "example: the run took $(( $(date +%s) - start )) s (exit status $status)"

last=$(ls "$out"/frame_*.pov | tail -n 1)
png=$(bash tools/render_povray.sh -w 640 -h 480 "$last")

# Then every shape: boxes, capsules and spheres dropped onto a pyramid of
# boxes (69 bodies, 2 000 steps; about 5 s on the CPU backend of 2 cores).
blocks=out/blocks
start=$(date +%s)
"build/example/examples/$target" blocks --out "$blocks" --frame-every 500 "$@" || status=$?
echo "example: the blocks run took $(( $(date +%s) - start )) s (exit status $status)"
blocks_png=$(bash tools/render_povray.sh -w 640 -h 480 "$(ls "$blocks"/frame_*.pov | tail -n 1)")
cat <<MSG
example: outputs in $out/ and $blocks/
  summary      $out/summary.json, $blocks/summary.json
  statistics   $out/stats.csv, $blocks/stats.csv (one row per step)
  frames       frame_*.vtk (spheres), shapes_*.vtk (boxes, capsules), fixed_*.vtk (ParaView), frame_*.pov
  pictures     $png
               $blocks_png
MSG
exit "$status"
