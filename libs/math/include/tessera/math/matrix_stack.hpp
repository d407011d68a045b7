#pragma once
// The notes' matrix stack: the top is the current transformation matrix (CTM).
#include <vector>

#include "tessera/core/error.hpp"
#include "tessera/math/types.hpp"

namespace tessera {

/// A stack of matrices (Mat3 for 2D, Mat4 for 3D) whose top is the CTM. It starts as [identity].
/// push() duplicates the top; pop() discards it (popping the last matrix throws InvalidInput, never UB);
/// multiply(T) sets CTM = CTM * T, so the transform written last acts first on the vertices (the notes, OpenGL).
template <class M>
class MatrixStack {
 public:
  MatrixStack() : stack_{M(1.0)} {}

  /// The current transformation matrix.
  const M& top() const { return stack_.back(); }
  /// Number of matrices on the stack (1 when nothing is pushed).
  size_t depth() const { return stack_.size(); }
  /// Replicates the CTM onto the top of the stack (gtPushMatrix).
  void push() { stack_.push_back(stack_.back()); }
  /// Pops the top of the stack and throws it away (gtPopMatrix). Throws InvalidInput on underflow.
  void pop() {
    if (stack_.size() <= 1) throw InvalidInput("matrix stack underflow: pop without a matching push");
    stack_.pop_back();
  }
  /// CTM = CTM * m (the transform applies before everything already on the stack).
  void multiply(const M& m) { stack_.back() = stack_.back() * m; }
  /// Replaces the CTM.
  void load(const M& m) { stack_.back() = m; }
  /// Replaces the CTM with the identity.
  void load_identity() { stack_.back() = M(1.0); }

 private:
  std::vector<M> stack_;
};

using MatrixStack2 = MatrixStack<Mat3>;
using MatrixStack3 = MatrixStack<Mat4>;

}  // namespace tessera
