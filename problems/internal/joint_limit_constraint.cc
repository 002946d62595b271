#include "problems/internal/joint_limit_constraint.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ccma/internal/constraint_set.h"
#include "ccma/internal/format.h"
#include "ccma/joint_coordinates.h"
#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"

namespace ccma {

double JointCoordinateGradient(const Model& model, const Joint& joint, const State& s, Eigen::RowVectorXd* dq_ds) {
  // The motor cost functions evaluate exactly the quantities q is made of
  // (at u = 0): their Jacobians give dq/ds without new derivative code.
  dq_ds->setZero(model.state_size());
  const double* poses[3] = {ConstraintSet::Pose(s, joint.body_a), ConstraintSet::Pose(s, joint.body_b), nullptr};
  const double zero = 0.0;
  poses[2] = &zero;
  double residuals[2];
  double J_A[2 * kPoseAmbientSize], J_B[2 * kPoseAmbientSize], J_u[2];
  double* jacobians[3] = {J_A, J_B, J_u};
  Eigen::Matrix<double, 1, 6> g_A, g_B;
  double q = 0;
  if (joint.type == JointType::kRevolute) {
    const ActuatedRevoluteCost cost(joint.e1_A, joint.e2_A, joint.w_B);
    cost.Evaluate(poses, residuals, jacobians);
    const double x = residuals[0] + 1.0, y = residuals[1];  // cos q, sin q (up to scale)
    const double norm2 = x * x + y * y;
    q = LimitCoordinate(joint, joint.q_home + std::atan2(y, x));
    for (int c = 0; c < 6; ++c) {
      g_A[c] = (x * J_A[kPoseAmbientSize + c] - y * J_A[c]) / norm2;
      g_B[c] = (x * J_B[kPoseAmbientSize + c] - y * J_B[c]) / norm2;
    }
  } else {
    const ActuatedPrismaticCost cost(joint.p_A, joint.p_B, joint.a_A);
    cost.Evaluate(poses, residuals, jacobians);
    q = joint.q_home + residuals[0];
    for (int c = 0; c < 6; ++c) {
      g_A[c] = J_A[c];
      g_B[c] = J_B[c];
    }
  }
  if (joint.body_a != kWorld) dq_ds->segment<6>(kPoseTangentSize * joint.body_a) += g_A;
  if (joint.body_b != kWorld) dq_ds->segment<6>(kPoseTangentSize * joint.body_b) += g_B;
  return q;
}

JointLimitConstraint::JointLimitConstraint(const Model& model, std::vector<int> joints)
    : model_(model), joints_(std::move(joints)) {}

double JointLimitConstraint::MaxViolation(const Eigen::VectorXd& /*u*/, const State& s) const {
  double worst = 0;
  for (int j : joints_) {
    const Joint& joint = model_.joints[j];
    const double q = LimitCoordinate(joint, JointCoordinate(joint, s));
    worst = std::max({worst, joint.lower - q, q - joint.upper});
  }
  return worst;
}

std::vector<int> JointLimitConstraint::AtOrBeyond(const Eigen::VectorXd& /*u*/, const State& s, double tolerance) const {
  std::vector<int> out;
  for (int j : joints_) {
    const Joint& joint = model_.joints[j];
    const double q = LimitCoordinate(joint, JointCoordinate(joint, s));
    if (q <= joint.lower + tolerance || q >= joint.upper - tolerance) out.push_back(j);
  }
  return out;
}

void JointLimitConstraint::AppendRows(const Eigen::VectorXd& /*u*/, const State& s, const SensitivityView& ds_du,
                                      const std::vector<int>& active, int first_row, LinearConstraints* rows) const {
  int row = first_row;
  Eigen::RowVectorXd dq_ds;
  for (int j : active) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinateGradient(model_, joint, s, &dq_ds);
    const double bound = std::abs(q - joint.lower) < std::abs(q - joint.upper) ? joint.lower : joint.upper;
    rows->A.row(row) = ds_du.RowTimes(dq_ds);
    rows->b[row] = bound - q;
    ++row;
  }
}

void JointLimitConstraint::AppendInequalities(const Eigen::VectorXd& u, const State& s,
                                              const SensitivityView& ds_du, double watch,
                                              std::vector<InequalityRow>* rows) const {
  Eigen::RowVectorXd dq_ds;
  for (int j : AtOrBeyond(u, s, watch)) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinateGradient(model_, joint, s, &dq_ds);
    const Eigen::RowVectorXd a = ds_du.RowTimes(dq_ds);
    if (q <= joint.lower + watch) rows->push_back({a, joint.lower - q});
    if (q >= joint.upper - watch) rows->push_back({-a, q - joint.upper});
  }
}

std::vector<int> JointLimitConstraint::WouldCross(const Eigen::VectorXd& /*u*/, const State& s, const SensitivityView& ds_du,
                                                  const Eigen::VectorXd& d, double tolerance) const {
  std::vector<int> out;
  Eigen::RowVectorXd dq_ds;
  const Eigen::VectorXd ds = ds_du.Times(d);
  for (int j : joints_) {
    const Joint& joint = model_.joints[j];
    const double q = JointCoordinateGradient(model_, joint, s, &dq_ds) + dq_ds.dot(ds);
    if (q < joint.lower - tolerance || q > joint.upper + tolerance) out.push_back(j);
  }
  return out;
}

std::string JointLimitConstraint::Report(const Eigen::VectorXd& u, const State& s, const std::vector<int>& active,
                                         ControlStepResult* result) const {
  result->max_limit_violation = std::max(0.0, MaxViolation(u, s));
  // The active joints are named while any limited joint sits at a bound.
  if (AtOrBeyond(u, s, 1e-8).empty()) return "";
  std::string text;
  for (int j : active) {
    const Joint& joint = model_.joints[j];
    const double q = LimitCoordinate(joint, JointCoordinate(joint, s));
    const bool upper = std::abs(q - joint.upper) < std::abs(q - joint.lower);
    text += std::string(text.empty() ? "" : ", ") + "joint '" + joint.name + "' at its " +
            (upper ? "upper" : "lower") + " limit " + FormatG(upper ? joint.upper : joint.lower) +
            (joint.type == JointType::kRevolute ? " rad" : " m");
  }
  return text;
}

}  // namespace ccma
