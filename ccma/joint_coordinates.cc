#include "ccma/joint_coordinates.h"

#include <cmath>

#include "ccma/internal/constraint_set.h"
#include "cost_functions/body_frame.h"

namespace ccma {

double JointCoordinate(const Joint& joint, const State& s) {
  const BodyFrame A(ConstraintSet::Pose(s, joint.body_a)), B(ConstraintSet::Pose(s, joint.body_b));
  if (joint.type == JointType::kRevolute) {
    const Eigen::Vector3d w = B.Rotate(joint.w_B);
    // atan2 in (-pi, pi]: the reported range (atan2(0, -1) = pi).
    return std::atan2(A.Rotate(joint.e2_A).dot(w), A.Rotate(joint.e1_A).dot(w));
  }
  if (joint.type == JointType::kPrismatic) {
    const Eigen::Vector3d d = (B.Rotate(joint.p_B) + B.p_WB) - (A.Rotate(joint.p_A) + A.p_WB);
    return A.Rotate(joint.a_A).dot(d);
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
    r.within_limits = !joint.limited || (r.q >= joint.lower - tolerance && r.q <= joint.upper + tolerance);
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
