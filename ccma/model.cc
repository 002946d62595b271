#include "ccma/model.h"

#include "cost_functions/actuated_prismatic_cost.h"
#include "cost_functions/actuated_revolute_cost.h"
#include "cost_functions/fixed_joint_cost.h"
#include "cost_functions/prismatic_joint_cost.h"
#include "cost_functions/revolute_joint_cost.h"
#include "cost_functions/spherical_joint_cost.h"
#include "cost_functions/universal_joint_cost.h"

namespace ccma {

const std::array<const char*, 6> kEndEffectorComponentNames = {
    "x", "y", "z", "roll", "pitch", "yaw"};

const char* JointTypeName(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "revolute";
    case JointType::kSpherical: return "spherical";
    case JointType::kUniversal: return "universal";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kFixed: return "fixed";
  }
  return "?";
}

int JointResidualCount(JointType type) {
  switch (type) {
    case JointType::kRevolute: return RevoluteJointCost::kNumResiduals;
    case JointType::kSpherical: return SphericalJointCost::kNumResiduals;
    case JointType::kUniversal: return UniversalJointCost::kNumResiduals;
    case JointType::kPrismatic: return PrismaticJointCost::kNumResiduals;
    case JointType::kFixed: return FixedJointCost::kNumResiduals;
  }
  return 0;
}

int ActuatorResidualCount(const Joint& joint) {
  if (!joint.actuated) return 0;
  return joint.type == JointType::kRevolute ? ActuatedRevoluteCost::kNumResiduals
                                             : ActuatedPrismaticCost::kNumResiduals;
}

int TranslationSpringCount(JointType type) {
  return type == JointType::kPrismatic ? 2 : 3;
}

int RotationSpringCount(JointType type) {
  switch (type) {
    case JointType::kRevolute: return 2;
    case JointType::kUniversal: return 1;
    case JointType::kPrismatic: return 3;
    case JointType::kFixed: return 3;
    case JointType::kSpherical: return 0;
  }
  return 0;
}

int Model::num_actuated_joints() const {
  int count = 0;
  for (const Joint& joint : joints) count += joint.actuated;
  return count;
}

int Model::FindJoint(const std::string& joint_name) const {
  for (int j = 0; j < static_cast<int>(joints.size()); ++j) {
    if (joints[j].name == joint_name) return j;
  }
  return -1;
}

std::vector<int> Model::effective_control_indices() const {
  std::vector<int> indices;
  int offset = 0;
  for (const MobileBase& base : mobile_bases) {
    const BaseKind& kind = KindOf(base);
    for (int i = 0; i < kind.num_controls(); ++i) {
      if (kind.IsEffective(base, i)) indices.push_back(offset + i);
    }
    offset += kind.num_controls();
  }
  for (const Joint& joint : joints) {
    if (joint.actuated) indices.push_back(joint.control);
  }
  return indices;
}

int Model::num_constraints() const {
  int rows = 0;
  for (const MobileBase& base : mobile_bases) rows += KindOf(base).num_residuals();
  for (const Joint& joint : joints) rows += JointResidualCount(joint.type) + ActuatorResidualCount(joint);
  return rows;
}

Eigen::VectorXd Model::home_controls() const {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(num_controls());
  int offset = 0;
  for (const MobileBase& base : mobile_bases) {
    const BaseKind& kind = KindOf(base);
    u.segment(offset, kind.num_controls()) = kind.HomeControls(base);
    offset += kind.num_controls();
  }
  for (const Joint& joint : joints) {
    if (joint.actuated) u[joint.control] = joint.q_home;
  }
  return u;
}

int Model::num_base_controls() const {
  int count = 0;
  for (const MobileBase& base : mobile_bases) count += KindOf(base).num_controls();
  return count;
}

int Model::base_control(int k) const {
  int offset = 0;
  for (int i = 0; i < k; ++i) offset += KindOf(mobile_bases[static_cast<size_t>(i)]).num_controls();
  return offset;
}

bool Model::compliant() const {
  for (const MobileBase& base : mobile_bases) {
    if (base.stiffness.given()) return true;
  }
  for (const Joint& joint : joints) {
    if (joint.stiffness.given()) return true;
  }
  return false;
}

int Model::FindBody(const std::string& body_name) const {
  for (int i = 0; i < num_bodies(); ++i) {
    if (bodies[i].name == body_name) return i;
  }
  return -1;
}

}  // namespace ccma
