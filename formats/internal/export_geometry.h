// What the URDF and SDFormat writers (urdf_writer.h, sdformat_writer.h) share:
// a model's joints and bodies in world coordinates at home, unique names for
// the frames the writers add, numbers written so that they read back exactly,
// and the spanning tree of the joint graph that URDF needs.
//
// Frames: W = world; all poses are at the model's home configuration; m, rad.
#ifndef CCMA_FORMATS_INTERNAL_EXPORT_GEOMETRY_H_
#define CCMA_FORMATS_INTERNAL_EXPORT_GEOMETRY_H_

#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ccma/model.h"

namespace ccma::internal {

// A body's frame in W at home (identity for kWorld).
Eigen::Isometry3d HomePose(const Model& model, int body);

// The body's mass as an <inertial> element in the frame of a link posed at
// X_WL (URDF: <origin>, <mass value>, <inertia ixx=...>; SDFormat: <pose>,
// <mass>, <inertia><ixx>...), each line after `indent`; "" without a mass.
std::string InertialXml(const Model& model, int body, const Eigen::Isometry3d& X_WL, bool sdformat,
                        const std::string& indent);
// The name of a body, or "world" for kWorld.
std::string BodyName(const Model& model, int body);

// A joint's geometry in W at home.
struct JointWorld {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // revolute, prismatic; universal: axes[0] (in A)
  Eigen::Vector3d axis2 = Eigen::Vector3d::UnitX();  // universal: axes[1] (in B)
};
JointWorld JointInWorld(const Model& model, const Joint& joint);

// Rotation whose columns are x, y and x cross y (a universal joint's frame).
Eigen::Matrix3d FrameFromAxes(const Eigen::Vector3d& x, const Eigen::Vector3d& y);

// `value` in the fewest digits (15 to 17) that read back to the same double.
std::string Number(double value);
// "x y z" (Number each).
std::string Triple(const Eigen::Vector3d& v);
// "[x, y, z]".
std::string YamlTriple(const Eigen::Vector3d& v);
// Roll, pitch, yaw of R (R = Rz(yaw) Ry(pitch) Rx(roll)), as "r p y".
std::string RpyText(const Eigen::Matrix3d& R);

// Names that are not yet taken: every body and joint name of the model, and
// "world", start taken; Claim returns `wanted`, or `wanted` with the first
// free "_2", "_3", ... suffix, and marks it taken.
class NameSet {
 public:
  explicit NameSet(const Model& model);
  std::string Claim(const std::string& wanted);

 private:
  std::set<std::string> taken_;
};

// The control-component names of the end-effector ("x", "yaw", ...).
std::vector<std::string> ControlledNames(const Model& model);

// The spanning tree of the graph whose nodes are world and the bodies and
// whose edges are the joints and the bases' joints (world -> base: planar or floating).
// Kruskal, keeping first the bases, then revolute, prismatic and universal
// joints, then fixed, then spherical joints, each group in file order.
struct SpanningTree {
  // Per body: the joint that joins it to its parent (-1: a base's joint from
  // world), the parent body (kWorld allowed), and whether the joint's
  // `between` runs child -> parent (its first body is the child).
  std::vector<int> parent_joint;
  std::vector<int> parent_body;
  std::vector<bool> reversed;
  std::vector<bool> in_tree;  // per model joint
  std::vector<int> order;     // bodies, each after its parent (breadth first from world)
};
// Which joints the tree keeps first. kUrdf: revolute, prismatic and universal
// alike. kMjcf: actuated, prismatic and universal joints before revolute
// (MuJoCo's equalities express a cut revolute, fixed or spherical joint, not
// the others, and carry no actuator).
enum class TreePreference { kUrdf, kMjcf };
// Throws std::invalid_argument when a body is not connected to world.
SpanningTree BuildSpanningTree(const Model& model, TreePreference preference = TreePreference::kUrdf);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_EXPORT_GEOMETRY_H_
