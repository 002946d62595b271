// The head-to-head results as a Markdown table (for benchmarks/RESULTS.md and
// benchmarks/results/simbody.md) and as JSON (benchmarks/results/simbody.json).
// Times in microseconds per step, distances in metres.
#ifndef CCMA_BENCHMARKS_SIMBODY_REPORT_H_
#define CCMA_BENCHMARKS_SIMBODY_REPORT_H_

#include <string>
#include <vector>

#include "benchmarks/simbody/head_to_head.h"

namespace ccma::simbody_benchmark {

// Where it ran: /proc/cpuinfo's model name and the number of online cores,
// and the Simbody version linked.
struct Machine {
  std::string cpu;
  int cores = 0;
  std::string simbody_version;
};
Machine DescribeMachine();

std::string MarkdownReport(const Machine& machine, const std::vector<HeadToHeadResult>& results);
std::string JsonReport(const Machine& machine, const std::vector<HeadToHeadResult>& results);

}  // namespace ccma::simbody_benchmark

#endif  // CCMA_BENCHMARKS_SIMBODY_REPORT_H_
