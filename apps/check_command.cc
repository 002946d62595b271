// `ccma check --model=FILE`: validate a model and analyse its mobility at home.
#include <gflags/gflags.h>

#include "apps/cli.h"
#include "apps/commands.h"
#include "apps/json_output.h"

DECLARE_string(model);

namespace ccma::cli {

int RunCheck(const std::vector<std::string>& args) {
  ParseFlags(args, {"model"}, "check");
  const Model model = LoadModelOrThrow(RequireFlag(FLAGS_model, "model", "check"));
  const ConstraintSet constraints(model);
  const State home = State::Home(model);
  const Eigen::VectorXd u = model.home_controls();
  const MobilityReport mobility = AnalyzeMobility(model, constraints, home, u);
  const ForwardOptions defaults;

  nlohmann::json out;
  out["model"] = model.name;
  out["bodies"] = model.num_bodies();
  out["mobile_bases"] = model.num_bases();
  out["joints"] = model.joints.size();
  out["state_size"] = model.state_size();
  out["controls"] = model.num_controls();
  out["effective_controls"] = model.effective_control_indices().size();
  out["constraints"] = constraints.num_rows();
  out["rigid_with_controls_fixed"] = mobility.rigid_with_controls_fixed;
  out["end_effector_dof"] = mobility.end_effector_dof;
  out["assembled_at_home"] = mobility.energy < defaults.assembly_tolerance;
  out["constraint_rank"] = mobility.constraint_rank;
  out["dof_with_controls_fixed"] = mobility.dof_with_controls_fixed;
  out["dof_with_controls_free"] = mobility.dof_with_controls_free;
  out["smallest_singular_value"] = mobility.smallest_singular_value;
  out["energy_at_home"] = mobility.energy;
  nlohmann::json controlled = nlohmann::json::array();
  for (int c = 0; c < 6; ++c) {
    if (model.end_effector.controlled[c]) controlled.push_back(kEndEffectorComponentNames[c]);
  }
  out["controlled"] = controlled;
  PrintJson(out);
  return 0;
}

}  // namespace ccma::cli
