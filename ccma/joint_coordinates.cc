#include "ccma/joint_coordinates.h"

#include <cmath>

#include "ccma/internal/constraint_set.h"
#include "cost_functions/body_frame.h"

namespace ccma {

double WrapJointCoordinate(const Joint& joint, double q) {
  if (joint.type != JointType::kRevolute) return q;
  const double wrapped = std::remainder(q, 2 * M_PI);  // [-pi, pi]
  return wrapped <= -M_PI ? wrapped + 2 * M_PI : wrapped;
}

double LimitCoordinate(const Joint& joint, double q) {
  if (joint.type != JointType::kRevolute || !joint.limited) return q;
  const double middle = 0.5 * (joint.lower + joint.upper);
  return middle + std::remainder(q - middle, 2 * M_PI);
}

double JointCoordinate(const Joint& joint, const State& s) {
  const BodyFrame A(ConstraintSet::Pose(s, joint.body_a)), B(ConstraintSet::Pose(s, joint.body_b));
  if (joint.type == JointType::kRevolute) {
    const Eigen::Vector3d w = B.Rotate(joint.w_B);
    // The motion since home, atan2 in (-pi, pi] (atan2(0, -1) = pi).
    const double motion = std::atan2(A.Rotate(joint.e2_A).dot(w), A.Rotate(joint.e1_A).dot(w));
    return joint.q_home == 0.0 ? motion : WrapJointCoordinate(joint, joint.q_home + motion);
  }
  if (joint.type == JointType::kPrismatic) {
    const Eigen::Vector3d d = (B.Rotate(joint.p_B) + B.p_WB) - (A.Rotate(joint.p_A) + A.p_WB);
    return joint.q_home + A.Rotate(joint.a_A).dot(d);
  }
  return 0.0;
}

std::vector<JointCoordinateReport> JointCoordinates(const Model& model, const State& s, double tolerance) {
  std::vector<JointCoordinateReport> out;
  for (int j = 0; j < static_cast<int>(model.joints.size()); ++j) {
    const Joint& joint = model.joints[j];
    if (!joint.has_coordinate()) continue;
    JointCoordinateReport r;
    r.joint = j;
    r.q = JointCoordinate(joint, s);
    const double q_limit = LimitCoordinate(joint, r.q);
    r.within_limits = !joint.limited || (q_limit >= joint.lower - tolerance && q_limit <= joint.upper + tolerance);
    out.push_back(r);
  }
  return out;
}

std::vector<std::string> LimitsViolated(const Model& model, const State& s, double tolerance) {
  std::vector<std::string> names;
  for (const JointCoordinateReport& r : JointCoordinates(model, s, tolerance)) {
    if (!r.within_limits) names.push_back(model.joints[r.joint].name);
  }
  return names;
}

}  // namespace ccma
