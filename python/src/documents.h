// The JSON documents of the `ccma` commands not yet built in documents/ (check,
// statics, simulate and control are: documents/*_document.h), for the Python
// results' to_dict(): the keys and values the command prints for the same
// inputs (docs/cli.md; python/tests/test_cli_agreement.py holds them equal,
// key by key). They are built from the document layer's values
// (documents/json_values.h, trajectory_csv.h, replay_report.h); the lines each
// command adds around them are mirrored here, one function per command, each
// naming the command file it follows, until they move to documents/ too.
#ifndef CCMA_PYTHON_SRC_DOCUMENTS_H_
#define CCMA_PYTHON_SRC_DOCUMENTS_H_

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analyses/design.h"
#include "ccma/ccma.h"
#include "python/src/pose_types.h"

namespace ccma::python {

// What `ccma trajectory` gathers over the steps it writes.
struct PathSummary {
  int steps = 0;
  double min_sigma = 0;  // smallest min_singular_value_dX_du over the steps
  double min_rcond = 0;  // smallest dG/ds pivot ratio over the steps
  int null_space_steps = 0;
  double secondary_objective = 0;  // the last step's
  ClearanceSummary path_clearance;  // the smallest over the steps (TrajectoryCsv::min_clearance)
  // compensate=True (`ccma trajectory --compensate`): the last row's loaded
  // configuration, which end_effector and clearance then describe, and the
  // rounds' tally (the JSON's `compensation`).
  std::optional<State> loaded_state;
  std::optional<CompensatedPath> compensation;
};

// apps/trajectory_command.cc: RunTrajectory (without "out": the caller adds it).
nlohmann::json TrajectoryDocument(const ControlProblem& control, const TrajectoryResult& r, std::size_t waypoints,
                                  const PathSummary& path);
// apps/plan_command.cc: RunPlan (without "out").
nlohmann::json PlanDocument(const ControlProblem& control, const PlanResult& r, std::size_t waypoints,
                            const ClearanceSummary& path_clearance);

// apps/design_command.cc: RunDesign (without "out"); `final_check`: the
// targets evaluated in the model as written.
nlohmann::json DesignDocument(const Model& model, const Model& designed, const DesignParameters& params,
                              const DesignResult& r, const std::vector<DesignTargetResult>& final_check,
                              const DesignOptions& options);

// apps/replay_command.cc: ReplayJson without "files" and "plots" (Python
// writes no files).
nlohmann::json ReplayDocument(const Model& model, const ReplayOptions& options, const ReplayResult& r);

// Sets `out[key]` to a clearance summary's numbers (apps/trajectory_command.cc:
// "min_on_path", "pair_on_path").
void AddPathClearance(const ClearanceSummary& path, nlohmann::json* out);

// Appends `text` to a "; "-separated warning (as the commands join theirs).
inline void JoinWarning(const std::string& text, std::string* warning) {
  *warning += (warning->empty() ? "" : "; ") + text;
}

}  // namespace ccma::python

#endif  // CCMA_PYTHON_SRC_DOCUMENTS_H_
