// The two node templates every operator builds: element i of the result is
// op(i, a) or op(i, a, b).
#pragma once

#include <cstddef>

#include "gpusolve/core/config.hpp"
#include "gpusolve/math/expr.hpp"
#include "gpusolve/math/expr_storage.hpp"

namespace gpusolve::math {

// An operation is a small functor: `op(i, a...)` computes element i, and
// `elementwise` says whether it reads element i of its operands only. One that
// reads other elements makes the node need a temporary in assign().
template <class Kind, class Op, class A>
class UnaryNode : public Expr<UnaryNode<Kind, Op, A>, Kind, typename A::scalar> {
 public:
  static constexpr bool needs_temporary = !Op::elementwise || A::needs_temporary;

  GPUSOLVE_HD UnaryNode(Op op, const A& a) : op_(op), a_(a) {}
  GPUSOLVE_HD typename A::scalar operator[](std::size_t i) const { return op_(i, a_); }

 private:
  Op op_;
  expr_storage_t<A> a_;
};

template <class Kind, class Op, class A, class B>
class BinaryNode : public Expr<BinaryNode<Kind, Op, A, B>, Kind, typename A::scalar> {
 public:
  static constexpr bool needs_temporary =
      !Op::elementwise || A::needs_temporary || B::needs_temporary;

  GPUSOLVE_HD BinaryNode(const A& a, const B& b) : a_(a), b_(b) {}
  GPUSOLVE_HD typename A::scalar operator[](std::size_t i) const { return Op{}(i, a_, b_); }

 private:
  expr_storage_t<A> a_;
  expr_storage_t<B> b_;
};

}  // namespace gpusolve::math
