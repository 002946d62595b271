#include "formats/joint_geometry.h"

#include <cmath>

#include <Eigen/Geometry>

namespace ccma {

void SetJointGeometry(const Model& model, const Eigen::Vector3d& p_W, const Eigen::Vector3d& a_W,
                      const Eigen::Vector3d& b_W, Joint* joint) {
  static const Body kGround;  // world: identity pose
  const Body& A = joint->body_a == kWorld ? kGround : model.bodies[joint->body_a];
  const Body& B = joint->body_b == kWorld ? kGround : model.bodies[joint->body_b];
  const Eigen::Matrix3d R_AW = A.R_WB_home.transpose(), R_BW = B.R_WB_home.transpose();
  joint->p_A = R_AW * (p_W - A.p_WB_home);
  joint->p_B = R_BW * (p_W - B.p_WB_home);
  const JointType type = joint->type;
  if (type == JointType::kRevolute || type == JointType::kPrismatic) {
    joint->a_A = R_AW * a_W;
    joint->a_B = R_BW * a_W;
    // Reference directions for q: any unit vector perpendicular to the axis.
    const Eigen::Vector3d helper = std::abs(a_W.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1_W = (helper - helper.dot(a_W) * a_W).normalized();
    joint->e1_A = R_AW * e1_W;
    joint->e2_A = R_AW * a_W.cross(e1_W);
    joint->w_B = R_BW * e1_W;
  }
  if (type == JointType::kUniversal) {
    joint->a_A = R_AW * a_W;
    joint->b_B = R_BW * b_W;
  }
  if (type == JointType::kFixed || type == JointType::kPrismatic) {
    joint->d1_A = R_AW * Eigen::Vector3d::UnitX();
    joint->d1_B = R_BW * Eigen::Vector3d::UnitX();
    joint->d2_A = R_AW * Eigen::Vector3d::UnitY();
    joint->d2_B = R_BW * Eigen::Vector3d::UnitY();
  }
}

}  // namespace ccma
