// Fixture kernels for tools/audit.py tests (see README.md here to regenerate
// the captured cuobjdump/ptxas text). Each kernel exercises a different audit
// column: fp32/fp64 FMA, local memory, shared and generic accesses, spills.
namespace demo {
template <typename T>
__global__ void triad(T* a, const T* b, const T* c, const T* d, int n) {
  int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) a[i] = b[i] + c[i] * d[i];
}
template __global__ void triad<float>(float*, const float*, const float*, const float*, int);
template __global__ void triad<double>(double*, const double*, const double*, const double*, int);
}  // namespace demo

// A local array indexed at run time cannot live in registers: LDL/STL.
__global__ void local_scratch(float* out, const int* idx, int n) {
  float buf[64];
  __shared__ float tile[64];
  int t = threadIdx.x;
  for (int k = 0; k < n; ++k) buf[k & 63] = out[t] * k;
  tile[t & 63] = buf[idx[t] & 63];
  __syncthreads();
  out[t] = sqrtf(tile[(t + 1) & 63]) + __sinf(buf[idx[t + 1] & 63]);
}

// fp64 arithmetic, float<->double conversions and generic LD/ST through a
// pointer that may point at shared or global memory.
__global__ void mixed(double* x, float* y, int n, bool use_shared) {
  __shared__ float s[128];
  int t = threadIdx.x;
  s[t & 127] = y[t];
  __syncthreads();
  float* p = use_shared ? s : y;
  double a = x[t] * x[t + n] + 1.0;
  a = a * (double)p[t & 127] - x[t + 2 * n];
  p[(t + 1) & 127] = (float)a;
  x[t] = a + sqrt(a);
}

// 24 live values under a 24-register cap: ptxas spills to the stack.
__global__ void __maxnreg__(24) spill(float* out, const float* in) {
  int t = threadIdx.x;
  float v[24];
#pragma unroll
  for (int k = 0; k < 24; ++k) v[k] = in[t + k * 32];
  float acc = 0.f;
#pragma unroll
  for (int k = 0; k < 24; ++k) acc += v[k] * v[23 - k];
  out[t] = acc;
}
