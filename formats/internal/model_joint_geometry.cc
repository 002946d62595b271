// A joint's `point`, `axis` (revolute, prismatic) and `axes` (universal):
// given once in world coordinates at home, stored in each body's frame.
#include <cmath>
#include <string>

#include "ccma/internal/format.h"
#include "formats/internal/model_parser.h"
#include "formats/joint_geometry.h"

namespace ccma {
namespace internal {
namespace {

// Cosine above which universal axes count as not perpendicular.
constexpr double kPerpendicularTolerance = 1e-6;

}  // namespace

// The joint's point and axes, from world coordinates at home into each
// body's frame.
void ModelParser::ParseJointGeometry(const YAML::Node& node, const std::string& path, Joint* joint) const {
  const Eigen::Vector3d p_W = r_.Vector3(r_.Require(node, "point", path), path + ".point", "m");
  Eigen::Vector3d a_W = Eigen::Vector3d::UnitZ(), b_W = Eigen::Vector3d::UnitX();
  const JointType type = joint->type;
  if (type == JointType::kRevolute || type == JointType::kPrismatic) {
    a_W = r_.Axis(r_.Require(node, "axis", path), path + ".axis");
  }
  if (type == JointType::kUniversal) {
    const YAML::Node axes = r_.Require(node, "axes", path);
    if (!axes.IsSequence() || axes.size() != 2) r_.Fail(axes, path + ".axes", "must be a list of 2 axes");
    a_W = r_.Axis(axes[0], path + ".axes[0]");
    b_W = r_.Axis(axes[1], path + ".axes[1]");
    const double cosine = a_W.dot(b_W);
    if (std::abs(cosine) > kPerpendicularTolerance) {
      r_.Fail(axes, path + ".axes", "the two axes must be perpendicular at home (cosine " + FormatG(cosine) + ")");
    }
    // Within the tolerance, make them exactly perpendicular (b moves in the
    // plane of a and b), so the model is assembled at home by construction.
    b_W = (b_W - cosine * a_W).normalized();
  }
  SetJointGeometry(model_, p_W, a_W, b_W, joint);
}

}  // namespace internal
}  // namespace ccma
