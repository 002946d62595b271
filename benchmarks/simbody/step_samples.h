// Per-step measurements of one solver along the track: wall time [us] and
// iterations of every step, over all laps; summarised by median and 95th
// percentile (a few slow steps, e.g. a page fault or another process on the
// shared cores, must not move the headline number).
#ifndef CCMA_BENCHMARKS_SIMBODY_STEP_SAMPLES_H_
#define CCMA_BENCHMARKS_SIMBODY_STEP_SAMPLES_H_

#include <vector>

namespace ccma::simbody_benchmark {

struct StepSamples {
  std::vector<double> time_us;     // wall time per step [us]
  std::vector<double> iterations;  // solver iterations per step (as the solver counts them)
  int failures = 0;                // steps that did not reach the tolerance

  void Add(double us, double its) {
    time_us.push_back(us);
    iterations.push_back(its);
  }
};

// The q-quantile (0..1, linear interpolation) of `values`; 0 if empty.
double Quantile(std::vector<double> values, double q);
inline double Median(const std::vector<double>& values) { return Quantile(values, 0.5); }

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_STEP_SAMPLES_H_
