// Detects one problem object used by two threads at once.
//
// Solves release the GIL, so two Python threads can be inside methods of one
// ccma.ForwardProblem or ccma.ControlProblem at the same time. The C++ problems
// are not thread-safe: both threads would write the same state and each would
// return numbers that are neither's. So every bound method of a problem holds a
// UsageGuard on it while it runs; a second thread that finds the problem in use
// gets RuntimeError ("ccma.ControlProblem is being used by another thread; use
// one problem per thread") and the first thread's solve goes on untouched.
//
// The in-use flags: one table of the objects in use, keyed by address, under a
// mutex (the bound classes are the library's own and have no room for a flag).
// An entry lives only while a method runs, so an address reused by a later
// object is never found stale. A ControlProblem is keyed by its inner
// ForwardProblem (ControlProblem.forward exposes it to Python): a solve of the
// one and any use of the other exclude each other.
#ifndef CCMA_PYTHON_SRC_USAGE_GUARD_H_
#define CCMA_PYTHON_SRC_USAGE_GUARD_H_

#include "problems/control_problem.h"
#include "problems/forward_problem.h"

namespace ccma::python {

class UsageGuard {
 public:
  // Marks the problem in use until destruction; throws std::runtime_error
  // (Python: RuntimeError) if another thread is using it. Takes no GIL.
  explicit UsageGuard(const ForwardProblem& p) : UsageGuard(&p, "ccma.ForwardProblem") {}
  explicit UsageGuard(const ControlProblem& p) : UsageGuard(&p.forward(), "ccma.ControlProblem") {}
  ~UsageGuard();
  UsageGuard(const UsageGuard&) = delete;
  UsageGuard& operator=(const UsageGuard&) = delete;

 private:
  UsageGuard(const void* key, const char* class_name);
  const void* key_;
};

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_USAGE_GUARD_H_
