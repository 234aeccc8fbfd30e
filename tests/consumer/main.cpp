// A downstream program: fills a structure-of-arrays VectorD2 through the CPU
// backend and checks the result. Exits non-zero on a wrong answer.
#include <cstdio>
#include <vector>

#include <gpusolve/gpusolve.hpp>

int main() {
  const std::size_t n = 37, pitch = 64;
  std::vector<float> storage(3 * pitch, -1.0f);
  gpusolve::VectorD2View<float> v{storage.data(), n, 3, pitch};
  gpusolve::launch(gpusolve::device::cpu{}, n, [v](std::size_t i) {
    for (std::size_t j = 0; j < 3; ++j) v(i, j) = static_cast<float>(10 * i + j);
  });
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      if (v(i, j) != static_cast<float>(10 * i + j)) {
        std::printf("consumer: wrong value at (%zu, %zu)\n", i, j);
        return 1;
      }
  std::printf("consumer: ok\n");
  return 0;
}
