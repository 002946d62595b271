// The document of `ccma trajectory` (docs/cli.md) and of Python's follow():
// what the path's steps say about the whole path (conditioning, secondary
// objective, clearance along it), where it ended, and the compensation's
// tally with --compensate / compensate=True. The rows are TrajectoryCsv's
// (documents/trajectory_csv.h).
#ifndef CCMA_DOCUMENTS_TRAJECTORY_DOCUMENT_H_
#define CCMA_DOCUMENTS_TRAJECTORY_DOCUMENT_H_

#include <cstddef>
#include <limits>
#include <optional>

#include "ccma/ccma.h"
#include "documents/document.h"

namespace ccma::documents {

// Gathered over the steps as they are made (Add, from the step callback).
// Steps that could not form the conditioning report 0 for it.
struct PathTally {
  double min_sigma = std::numeric_limits<double>::infinity();  // smallest min_singular_value_dX_du
  double min_rcond = std::numeric_limits<double>::infinity();  // smallest dG/ds pivot ratio
  int null_space_steps = 0;
  double secondary_objective = 0;  // the last step's
  std::optional<State> last_state;  // the last step's configuration (the loaded one when compensated)

  void Add(const TrajectoryStep& step);
};

// A followed path: the problem after it (its model, options, controls and
// state), the result, and what was gathered along the way.
struct TrajectorySolution {
  const ControlProblem* control = nullptr;
  TrajectoryResult result;
  std::size_t waypoints = 0;
  PathTally tally;
  ClearanceSummary path_clearance;  // TrajectoryCsv::min_clearance()
  // A compensated path: the rounds' tally; end_effector and clearance then
  // describe the last step's loaded configuration.
  std::optional<CompensatedPath> compensation;
};

// The document without "out" (the caller's file, when there is one).
// Document::warnings: the clearance's when below the margin, then the
// result's warning.
Document TrajectoryDocument(const TrajectorySolution& s);

// Sets out["clearance"]["min_on_path"] and ["pair_on_path"] from the
// smallest clearance over a path's rows (nothing when none was checked).
void AddPathClearance(const ClearanceSummary& path, nlohmann::json* out);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_TRAJECTORY_DOCUMENT_H_
