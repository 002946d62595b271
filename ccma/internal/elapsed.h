// Wall-clock time since a start, for the solve_time_ms reported by the solvers.
#ifndef CCMA_INTERNAL_ELAPSED_H_
#define CCMA_INTERNAL_ELAPSED_H_

#include <chrono>

namespace ccma {

// Milliseconds of std::chrono::steady_clock since `start`.
inline double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ccma

#endif  // CCMA_INTERNAL_ELAPSED_H_
