// AllocationLabel: what the library is allocating for, named in an
// OutOfMemoryError beside the bytes ("for contacts", "for the solver").
#pragma once

namespace gpusolve::memory {

// Set around a growth point for the scope's lifetime (innermost wins, per
// thread): an allocation that fails inside it says what it was for.
class AllocationLabel {
 public:
  explicit AllocationLabel(const char* what) : outer_(current()) { current() = what; }
  ~AllocationLabel() { current() = outer_; }
  AllocationLabel(const AllocationLabel&) = delete;
  AllocationLabel& operator=(const AllocationLabel&) = delete;

  // The innermost label of this thread, or nullptr.
  static const char* now() { return current(); }

 private:
  static const char*& current() {
    thread_local const char* label = nullptr;
    return label;
  }
  const char* outer_;
};

}  // namespace gpusolve::memory
