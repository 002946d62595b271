// A joint's `point`, `axis` (revolute, prismatic) and `axes` (universal):
// given once in world coordinates at home, stored in each body's frame.
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"

namespace ccma {
namespace internal {
namespace {

// Cosine above which universal axes count as not perpendicular.
constexpr double kPerpendicularTolerance = 1e-6;

}  // namespace

// The joint's point and axes, from world coordinates at home into each
// body's frame.
void ModelParser::ParseJointGeometry(const YAML::Node& node, const std::string& path, Joint* joint) const {
  static const Body kGround;  // world: identity pose
  const Body& A = joint->body_a == kWorld ? kGround : model_.bodies[joint->body_a];
  const Body& B = joint->body_b == kWorld ? kGround : model_.bodies[joint->body_b];
  const Eigen::Vector3d p_W = r_.Vector3(r_.Require(node, "point", path), path + ".point", "m");
  joint->p_A = A.R_WB_home.transpose() * (p_W - A.p_WB_home);
  joint->p_B = B.R_WB_home.transpose() * (p_W - B.p_WB_home);

  const JointType type = joint->type;
  if (type == JointType::kRevolute || type == JointType::kPrismatic) {
    const Eigen::Vector3d a_W = r_.Axis(r_.Require(node, "axis", path), path + ".axis");
    joint->a_A = A.R_WB_home.transpose() * a_W;
    joint->a_B = B.R_WB_home.transpose() * a_W;
    // Reference directions for q: any unit vector perpendicular to the axis.
    const Eigen::Vector3d helper = std::abs(a_W.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1_W = (helper - helper.dot(a_W) * a_W).normalized();
    joint->e1_A = A.R_WB_home.transpose() * e1_W;
    joint->e2_A = A.R_WB_home.transpose() * a_W.cross(e1_W);
    joint->w_B = B.R_WB_home.transpose() * e1_W;
  }
  if (type == JointType::kUniversal) {
    const YAML::Node axes = r_.Require(node, "axes", path);
    if (!axes.IsSequence() || axes.size() != 2) r_.Fail(axes, path + ".axes", "must be a list of 2 axes");
    const Eigen::Vector3d a_W = r_.Axis(axes[0], path + ".axes[0]");
    const Eigen::Vector3d b_W = r_.Axis(axes[1], path + ".axes[1]");
    const double cosine = a_W.dot(b_W);
    if (std::abs(cosine) > kPerpendicularTolerance) {
      r_.Fail(axes, path + ".axes", "the two axes must be perpendicular at home (cosine " + FormatG(cosine) + ")");
    }
    // Within the tolerance, make them exactly perpendicular (b moves in the
    // plane of a and b), so the model is assembled at home by construction.
    const Eigen::Vector3d b_W_exact = (b_W - cosine * a_W).normalized();
    joint->a_A = A.R_WB_home.transpose() * a_W;
    joint->b_B = B.R_WB_home.transpose() * b_W_exact;
  }
  if (type == JointType::kFixed || type == JointType::kPrismatic) {
    joint->d1_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
    joint->d1_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitX();
    joint->d2_A = A.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
    joint->d2_B = B.R_WB_home.transpose() * Eigen::Vector3d::UnitY();
  }
}

}  // namespace internal
}  // namespace ccma
