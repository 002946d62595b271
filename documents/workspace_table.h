// The table of a workspace map: `ccma workspace --out`'s CSV and Python's
// WorkspaceResult.table, one row per sample (docs/cli.md, "ccma workspace").
#ifndef CCMA_DOCUMENTS_WORKSPACE_TABLE_H_
#define CCMA_DOCUMENTS_WORKSPACE_TABLE_H_

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "analyses/workspace.h"
#include "documents/table.h"

namespace ccma::documents {

// The columns computed after the map, per sample (0 where not reached):
// ee_std_m [m] (analyses/precision.h EndEffectorPositionStd) and, for a
// compliant model, stiffness_min_N_per_m [N/m] (analyses/compliance.h
// SmallestTranslationalStiffness; +inf, an empty cell, where every
// translation is rigid).
struct WorkspaceComputedColumns {
  Eigen::VectorXd ee_std_m;
  Eigen::VectorXd stiffness_min;  // empty for a rigid model
};

// The computed columns of one sample's (state, controls) when reached.
double WorkspaceEeStd(const Model& model, const State& s, const Eigen::VectorXd& u);
double WorkspaceStiffnessMin(const Model& model, const State& s, const Eigen::VectorXd& u);

// Both columns for every sample; `on_row(rows done)` after each sample's
// (it may throw to stop: a work bound). Throws std::invalid_argument as
// SmallestTranslationalStiffness does.
WorkspaceComputedColumns ComputeWorkspaceColumns(const Model& model, const std::vector<WorkspaceSample>& samples,
                                                 const std::function<void(long long)>& on_row = nullptr);

// What one row's computed columns take at home [s] (for a run's estimate).
// Throws std::invalid_argument when a compliant model's statics is beyond
// its bounds (ComputeStatics).
double WorkspaceRowSeconds(const Model& model);

// Per sample: the controlled components (x, y, z, roll, pitch, yaw, those the
// model controls), reachable, residual_energy, sigma_min (0 where not
// reached), error, rcond, max_limit_violation, limited_by, wave, start,
// ee_std_m, stiffness_min_N_per_m (a compliant model only), u0, u1, ...
// (empty where not reached).
Table WorkspaceTable(const Model& model, const std::vector<WorkspaceSample>& samples,
                     const WorkspaceComputedColumns& computed);

}  // namespace ccma::documents

#endif  // CCMA_DOCUMENTS_WORKSPACE_TABLE_H_
