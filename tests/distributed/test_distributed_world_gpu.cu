// The distributed tests on the GPU backend: every rank's World on the one GPU
// (run there with mpirun; tools/gpu_suite.sh).
#define GPUSOLVE_TEST_GPU
#include "test_distributed_world.cpp"
