// Math expressions on Global types in a kernel over device memory give the
// numbers the host gets from the same functor (up to FMA contraction).
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "catch_compat.hpp"
#include "gpusolve/container/vector_d2_offset.hpp"
#include "gpusolve/container/vector_view.hpp"
#include "gpusolve/core/error.hpp"
#include "gpusolve/core/launch.hpp"
#include "gpusolve/math.hpp"

using namespace gpusolve;
using namespace gpusolve::math;

namespace {

constexpr std::size_t nx = 1000, pitch = 1024;

// One rigid-body-like update of element i, mixing Global and value types and
// assigning expressions that read their own target.
template <class T>
struct BodyStep {
  VectorD2View<T> x, v, w, rot, inertia, q;
  VectorD2Offset<3> o3;
  VectorD2Offset<9> o9;
  VectorD2Offset<4> o4;
  T dt;

  GPUSOLVE_HD void operator()(std::size_t i) const {
    Vector3Global<T> xg(x, o3, i), vg(v, o3, i), wg(w, o3, i);
    Matrix3x3Global<T> rg(rot, o9, i), ig(inertia, o9, i);
    QuaternionGlobal<T> qg(q, o4, i);
    const Vector3<T> r = rotate(qg, vg);
    xg = xg + vg * dt + r - (r % wg) * dt;
    vg = vg % wg;
    wg = rg * (inverse_spd(ig) * (transpose(rg) * wg));
    qg = integrate_orientation(qg, wg, dt);
    rg = to_rotation_matrix(qg) * rg;
    ig = rotate_tensor(rg, ig);
    xg += -r / T(2);
    vg *= dt;
  }
};

// One SoA field: host data (padding included) and its device copy.
template <class T>
struct Field {
  std::size_t rows;
  std::vector<T> host;
  T* device = nullptr;

  Field(std::size_t rows_, std::mt19937& rng) : rows(rows_), host(rows_ * pitch, T(-7)) {
    std::uniform_real_distribution<double> u(-1, 1);
    for (std::size_t j = 0; j < rows; ++j)
      for (std::size_t i = 0; i < nx; ++i) host[j * pitch + i] = static_cast<T>(u(rng));
    GPUSOLVE_CUDA_CHECK(cudaMalloc(&device, host.size() * sizeof(T)));
    GPUSOLVE_CUDA_CHECK(cudaMemcpy(device, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice));
  }
  VectorD2View<T> host_view() { return {host.data(), nx, rows, pitch}; }
  VectorD2View<T> device_view() { return {device, nx, rows, pitch}; }
  std::vector<T> from_device() {
    std::vector<T> out(host.size());
    GPUSOLVE_CUDA_CHECK(cudaMemcpy(out.data(), device, out.size() * sizeof(T), cudaMemcpyDeviceToHost));
    GPUSOLVE_CUDA_CHECK(cudaFree(device));
    device = nullptr;
    return out;
  }
};

// An SPD inertia tensor per element (the kernel inverts it) and a unit quaternion.
template <class T>
void make_physical(Field<T>& inertia, Field<T>& q) {
  for (std::size_t i = 0; i < nx; ++i) {
    auto e = [&](std::size_t k) -> T& { return inertia.host[k * pitch + i]; };
    e(1) = e(3);
    e(2) = e(6);
    e(5) = e(7);
    for (std::size_t k : {0, 4, 8}) e(k) = 3 + std::abs(e(k));  // diagonally dominant
    T n = 0;
    for (std::size_t k = 0; k < 4; ++k) n += q.host[k * pitch + i] * q.host[k * pitch + i];
    for (std::size_t k = 0; k < 4; ++k) q.host[k * pitch + i] /= std::sqrt(n);
  }
}

}  // namespace

TEMPLATE_TEST_CASE("Global expressions agree between a kernel and the host", "[math][gpu]", float, double) {
  using T = TestType;
  const double tol = sizeof(T) == sizeof(float) ? 1e-4 : 1e-11;
  std::mt19937 rng(51);
  Field<T> x(3, rng), v(3, rng), w(3, rng), rot(9, rng), inertia(9, rng), q(4, rng);
  make_physical(inertia, q);
  for (Field<T>* f : {&inertia, &q})
    GPUSOLVE_CUDA_CHECK(cudaMemcpy(f->device, f->host.data(), f->host.size() * sizeof(T), cudaMemcpyHostToDevice));

  const T dt = T(0.01);
  const VectorD2Offset<3> o3(pitch);
  const VectorD2Offset<9> o9(pitch);
  const VectorD2Offset<4> o4(pitch);
  launch(device::gpu{}, nx,
         BodyStep<T>{x.device_view(), v.device_view(), w.device_view(), rot.device_view(),
                     inertia.device_view(), q.device_view(), o3, o9, o4, dt});
  GPUSOLVE_CUDA_CHECK(cudaDeviceSynchronize());
  launch(device::cpu{}, nx,
         BodyStep<T>{x.host_view(), v.host_view(), w.host_view(), rot.host_view(),
                     inertia.host_view(), q.host_view(), o3, o9, o4, dt});

  for (Field<T>* f : {&x, &v, &w, &rot, &inertia, &q}) {
    const std::vector<T> got = f->from_device();
    std::size_t mismatches = 0;
    for (std::size_t k = 0; k < got.size(); ++k)
      if (!(std::abs(double(got[k]) - double(f->host[k])) <= tol * (1 + std::abs(double(f->host[k]))))) {
        if (mismatches++ < 5) UNSCOPED_INFO("entry " << k << ": gpu " << got[k] << ", host " << f->host[k]);
      }
    CHECK(mismatches == 0);
  }
}
