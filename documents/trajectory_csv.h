// The CSV of `ccma trajectory` and `ccma plan` (cli.md): one row per control
// step, every column name carrying its unit; clearance columns only with
// collision geometry, effort columns only with masses or limits.
#ifndef CCMA_DOCUMENTS_TRAJECTORY_CSV_H_
#define CCMA_DOCUMENTS_TRAJECTORY_CSV_H_

#include <ostream>

#include "ccma/ccma.h"

namespace ccma::documents {

// Writes rows as steps arrive; keeps the smallest clearance of all rows.
class TrajectoryCsv {
 public:
  TrajectoryCsv(const Model& model, std::ostream& csv);
  void Write(const TrajectoryStep& step);
  // The smallest clearance over the rows written (any = false: none checked).
  const ClearanceSummary& min_clearance() const { return path_clearance_; }

 private:
  const Model& model_;
  std::ostream& csv_;
  const CollisionModel collision_;
  ClearanceSummary path_clearance_;
  const bool efforts_;  // statics columns (masses, payload or effort limits given)
  const EffortEvaluator effort_evaluator_;
};

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_TRAJECTORY_CSV_H_
