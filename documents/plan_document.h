// The document of `ccma plan` (docs/cli.md) and of Python's plan(): how the
// whole-path optimisation (problems/plan.h) went against the greedy path it
// started from, how it stopped and was finished, and where it ended. The
// rows are TrajectoryCsv's (documents/trajectory_csv.h).
#ifndef CCMA_DOCUMENTS_PLAN_DOCUMENT_H_
#define CCMA_DOCUMENTS_PLAN_DOCUMENT_H_

#include <cstddef>

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// `control` after the plan (its controls and state are the last step's),
// `waypoints` the path's count, `path_clearance` the smallest clearance over
// the rows (TrajectoryCsv::min_clearance). The document without "out".
// Document::warnings: the clearance's when below the margin, then the
// "warning" (the greedy path kept, waypoints not reached).
Document PlanDocument(const ControlProblem& control, const PlanResult& result, std::size_t waypoints,
                      const ClearanceSummary& path_clearance);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_PLAN_DOCUMENT_H_
