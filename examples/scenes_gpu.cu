// The CUDA build of gpusolve_scenes: the same source, compiled by nvcc so that --backend gpu runs.
#include "scenes.cpp"
