// Work bounded by its estimated cost in Python (analyses/work_estimate.h;
// docs/security.md, "Work bounded by its cost"): ccma.workspace and
// ccma.design say a long run's estimate and progress on sys.stderr and
// refuse one estimated beyond max_minutes (ccma.WorkBoundError), as the
// commands do with --max_minutes.
#ifndef CCMA_PYTHON_SRC_WORK_BOUND_H_
#define CCMA_PYTHON_SRC_WORK_BOUND_H_

#include <string>

#include "analyses/work_estimate.h"

namespace ccma::python {

// For ccma.FUNCTION counting `noun`, bounded by `max_minutes` (ValueError
// outside (0, 10080]): lines on sys.stderr (the GIL taken to write them).
WorkEstimateOptions PythonWorkEstimate(const std::string& function, const std::string& noun, double max_minutes);

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_WORK_BOUND_H_
