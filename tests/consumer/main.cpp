// A downstream program: moves points stored in a structure-of-arrays VectorD2
// with an expression on Vector3Global, through the CPU backend, and checks the
// result. Exits non-zero on a wrong answer.
#include <cmath>
#include <cstdio>

#include <gpusolve/gpusolve.hpp>

int main() {
  using namespace gpusolve;
  const std::size_t n = 37;  // not a multiple of the 32-element padding
  VectorD2<float, device::cpu> pos(n, 3), vel(n, 3);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      pos(i, j) = static_cast<float>(i + j);
      vel(i, j) = static_cast<float>(j) - 1.0f;
    }
  const float dt = 0.5f;
  auto p = pos.view();
  auto v = vel.view();
  const VectorD2Offset<3> off(p.pitch);
  launch(device::cpu{}, n, [=](std::size_t i) {
    math::Vector3Global<float> x(p, off, i), u(v, off, i);
    x = x + u * dt;
  });
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const float want = static_cast<float>(i + j) + (static_cast<float>(j) - 1.0f) * dt;
      if (std::fabs(pos(i, j) - want) > 1e-6f) {
        std::printf("consumer: wrong value at (%zu, %zu): %g, want %g\n", i, j, pos(i, j), want);
        return 1;
      }
    }
  std::printf("consumer: ok (%zu points, pitch %zu)\n", n, pos.pitch());
  return 0;
}
