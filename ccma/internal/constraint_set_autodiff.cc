// ConstraintSet::MakeAutoDiffTwins: every constraint block's cost as
// ceres::AutoDiffCostFunction over its templated residual (`ccma bench`
// compares them with the analytic costs; the derivative tests check one
// against the other). The twins themselves are compiled in
// cost_functions/autodiff_twins.cc.
#include <memory>
#include <vector>

#include "ccma/internal/constraint_set.h"
#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/fixed_joint_cost.h"
#include "cost_functions/prismatic_joint_cost.h"
#include "cost_functions/revolute_joint_cost.h"
#include "cost_functions/spherical_joint_cost.h"
#include "cost_functions/universal_joint_cost.h"

namespace ccma {
namespace {

std::unique_ptr<ceres::CostFunction> MakeJointTwin(const Joint& j) {
  switch (j.type) {
    case JointType::kRevolute:
      return std::unique_ptr<ceres::CostFunction>(MakeRevoluteJointAutoDiff(j.p_A, j.p_B, j.a_A, j.a_B));
    case JointType::kSpherical:
      return std::unique_ptr<ceres::CostFunction>(MakeSphericalJointAutoDiff(j.p_A, j.p_B));
    case JointType::kUniversal:
      return std::unique_ptr<ceres::CostFunction>(MakeUniversalJointAutoDiff(j.p_A, j.p_B, j.a_A, j.b_B));
    case JointType::kPrismatic:
      return std::unique_ptr<ceres::CostFunction>(
          MakePrismaticJointAutoDiff(j.p_A, j.p_B, j.a_A, j.d1_A, j.d1_B, j.d2_A, j.d2_B));
    case JointType::kFixed:
      return std::unique_ptr<ceres::CostFunction>(
          MakeFixedJointAutoDiff(j.p_A, j.p_B, j.d1_A, j.d1_B, j.d2_A, j.d2_B));
  }
  return nullptr;
}

std::unique_ptr<ceres::CostFunction> MakeActuatorTwin(const Joint& j) {
  if (j.type == JointType::kRevolute) {
    return std::unique_ptr<ceres::CostFunction>(MakeActuatedRevoluteAutoDiff(j.e1_A, j.e2_A, j.w_B, j.q_home));
  }
  return std::unique_ptr<ceres::CostFunction>(MakeActuatedPrismaticAutoDiff(j.p_A, j.p_B, j.a_A, j.q_home));
}

}  // namespace

std::vector<std::unique_ptr<ceres::CostFunction>> ConstraintSet::MakeAutoDiffTwins(
    const Model& model) const {
  std::vector<std::unique_ptr<ceres::CostFunction>> twins;
  for (const Joint& joint : model.joints) {
    twins.push_back(MakeJointTwin(joint));
    if (joint.actuated) twins.push_back(MakeActuatorTwin(joint));
  }
  for (const MobileBase& base : model.mobile_bases) {
    for (BaseConstraint& c : KindOf(base).Constraints(base, /*autodiff=*/true)) twins.push_back(std::move(c.cost));
  }
  return twins;
}

}  // namespace ccma
