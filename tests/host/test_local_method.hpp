// A method of a user's own that does not run distributed: projected Jacobi's
// solver behind the Solver concept's solve() alone, without set_exchange
// (every method of the library's runs distributed). For the tests that a
// World and a DistributedWorld refuse such a method.
#pragma once

#include "gpusolve/rbd/solvers/jacobi.hpp"

namespace rbd_test {

struct LocalJacobi {
  template <class Device, class T, class Model>
  struct solver {
    using Inner = gpusolve::rbd::JacobiSolver<Device, T, Model>;
    static constexpr double default_omega = Inner::default_omega;
    gpusolve::rbd::SolverStats<T> solve(gpusolve::rbd::Bodies<Device, T>& b, gpusolve::rbd::Contacts<Device, T, Model>& c,
                                        const gpusolve::rbd::SolverSettings<T>& s, gpusolve::stream_t stream,
                                        bool from_x) {
      return inner.solve(b, c, s, stream, from_x);
    }
    Inner inner;
  };
  static constexpr const char* name = "local-jacobi";
};

}  // namespace rbd_test
