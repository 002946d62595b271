#include "documents/json_values.h"

#include <algorithm>
#include <cmath>

#include "ccma/internal/format.h"

namespace ccma::documents {

nlohmann::json ToJson(const Eigen::VectorXd& v) {
  return nlohmann::json(std::vector<double>(v.data(), v.data() + v.size()));
}

nlohmann::json ToJson(const EndEffectorPose& pose) {
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r) {
    rotation.push_back({pose.rotation(r, 0), pose.rotation(r, 1), pose.rotation(r, 2)});
  }
  return {{"position", ToJson(pose.position)}, {"rotation", rotation}, {"rpy", ToJson(pose.rpy)}};
}

nlohmann::json BodiesToJson(const Model& model, const State& s) {
  nlohmann::json bodies = nlohmann::json::array();
  for (int i = 0; i < model.num_bodies(); ++i) {
    const Eigen::Quaterniond q = s.q_WB(i);
    bodies.push_back({{"name", model.bodies[i].name},
                      {"position", ToJson(s.p_WB(i))},
                      {"rpy", ToJson(RpyFromRotation(s.R_WB(i)))},
                      {"quaternion", {q.w(), q.x(), q.y(), q.z()}}});
  }
  return bodies;
}

nlohmann::json JointsToJson(const Model& model, const State& s) {
  nlohmann::json joints = nlohmann::json::array();
  for (const JointCoordinateReport& r : JointCoordinates(model, s)) {
    const Joint& joint = model.joints[r.joint];
    nlohmann::json entry = {{"name", joint.name}, {"type", JointTypeName(joint.type)}, {"q", r.q},
                            {"actuated", joint.actuated}};
    if (joint.limited) entry["limits"] = {joint.lower, joint.upper};
    joints.push_back(entry);
  }
  return joints;
}

nlohmann::json LimitsViolatedToJson(const Model& model, const State& s) {
  return nlohmann::json(LimitsViolated(model, s));
}

nlohmann::json ClearanceToJson(const Model& model, const State& s) {
  const CollisionModel collision(model);
  const ClearanceSummary c = MinimumClearance(collision, s);
  if (!c.any) return nullptr;
  return {{"min", c.min}, {"pair", {c.a, c.b}}, {"margin", collision.margin()}, {"below_margin", c.min < collision.margin() - 1e-9}};
}

void AddClearance(const Model& model, const State& s, nlohmann::json* out, std::vector<std::string>* warnings) {
  const nlohmann::json clearance = ClearanceToJson(model, s);
  if (clearance.is_null()) return;
  (*out)["clearance"] = clearance;
  if (clearance["below_margin"].get<bool>() && warnings) {
    warnings->push_back("clearance " + FormatG(clearance["min"].get<double>()) + " m between '" +
                        clearance["pair"][0].get<std::string>() + "' and '" + clearance["pair"][1].get<std::string>() +
                        "' is below the margin " + FormatG(clearance["margin"].get<double>()) + " m");
  }
}

namespace {

nlohmann::json MatrixRows(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) rows.push_back(ToJson(Eigen::VectorXd(m.row(r).transpose())));
  return rows;
}

}  // namespace

void AddComplianceJson(const StaticsReport& report, nlohmann::json* out) {
  if (!report.compliant) return;
  const ComplianceReport& c = report.compliance;
  (*out)["compliant_reactions"] = true;
  (*out)["deflection"] = {{"end_effector", ToJson(Eigen::VectorXd(c.deflection))},
                          {"max_body_m", c.max_body_m},
                          {"held", c.held}};
  (*out)["ee_compliance"] = MatrixRows(c.ee_compliance);
  if (c.stiffness_defined) {
    (*out)["ee_stiffness"] = MatrixRows(c.ee_stiffness);
  } else {
    (*out)["ee_stiffness"] = nullptr;
    (*out)["ee_stiffness_note"] = c.stiffness_note;
  }
  if (c.controlled_stiffness_defined) {
    (*out)["controlled_stiffness"] = MatrixRows(c.controlled_stiffness);
  } else {
    (*out)["controlled_stiffness"] = nullptr;
    (*out)["controlled_stiffness_note"] = c.controlled_stiffness_note;
  }
  (*out)["most_compliant"] = {{"direction", ToJson(Eigen::VectorXd(c.most_compliant_direction))},
                              {"compliance", c.most_compliant}};
}

void AddLoadedJson(const Model& model, const LoadedEquilibrium& loaded, nlohmann::json* out) {
  (*out)["end_effector"] = ToJson(ComputeEndEffectorPose(model, loaded.state));
  (*out)["bodies"] = BodiesToJson(model, loaded.state);
  (*out)["joints"] = JointsToJson(model, loaded.state);
  (*out)["deflection"] = {{"end_effector", ToJson(Eigen::VectorXd(loaded.deflection))},
                          {"max_body_m", loaded.max_body_m},
                          {"held", loaded.held}};
  (*out)["loaded"] = {{"converged", loaded.converged},
                      {"iterations", loaded.iterations},
                      {"load_fraction", loaded.load_fraction},
                      {"unbalanced_load", loaded.unbalanced},
                      {"yields", ToJson(loaded.yields)}};
}

void AddCompensationJson(const Model& model, const EndEffectorPose& rigid, const CompensatedResult& c,
                         nlohmann::json* out) {
  AddLoadedJson(model, c.loaded, out);
  (*out)["converged"] = c.converged;
  (*out)["error"] = c.miss;
  (*out)["limits_violated"] = LimitsViolatedToJson(model, c.loaded.state);
  (*out)["compensation"] = {{"converged", c.converged},
                            {"rounds", c.rounds},
                            {"miss", c.miss},
                            {"aim", {c.aim.position[0], c.aim.position[1], c.aim.position[2], c.aim.rpy[0],
                                     c.aim.rpy[1], c.aim.rpy[2]}},
                            {"rigid_end_effector", ToJson(rigid)}};
}

nlohmann::json SecondaryJson(const ControlOptions::Secondary& secondary, int null_space_steps, double objective) {
  nlohmann::json out = {{"null_space_steps", null_space_steps},
                        {"singularity_weight", secondary.singularity_weight},
                        {"singularity_threshold", secondary.singularity_threshold},
                        {"pivot_weight", secondary.pivot_weight},
                        {"pivot_threshold", secondary.pivot_threshold},
                        {"spread_weight", secondary.spread_weight},
                        {"clearance_m", secondary.clearance_m},
                        {"travel_weight", secondary.travel_weight}};
  // Phi is infinite only where dG/ds could not be factorised: no number then.
  if (std::isfinite(objective)) out["objective"] = objective;
  return out;
}

}  // namespace ccma::documents
