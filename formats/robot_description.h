// A robot read from a URDF (plus closure file) or SDFormat file, before it
// becomes a Model: links with their world poses in the source's zero
// configuration, joints with their world geometry there, the loop closures
// and the actuated joints. The readers (urdf_reader.h, sdformat_reader.h)
// fill it; analyses/robot_import.h assembles it into a Model; nothing here
// depends on the source format.
//
// Frames: W = world (the source's world or root frame, z up). X_WL is a
// link's frame in W at the zero configuration; all lengths in metres.
#ifndef CCMA_FORMATS_ROBOT_DESCRIPTION_H_
#define CCMA_FORMATS_ROBOT_DESCRIPTION_H_

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ccma/model.h"

namespace ccma {

// The name the source uses for the ground (a URDF root link called `world`,
// an SDFormat joint's parent `world`).
constexpr const char* kRobotWorld = "world";

// Links, joints and closures of a robot that ccma imports, each: generous
// (real robots have tens to hundreds) and well inside what the loader takes
// back (4 MiB, ccma/limits.h; a 2,000-link chain writes 0.34 MB, and
// imports in 2 s and 53 MB from a 98,000-element URDF).
constexpr int kMaxRobotLinks = 2000;
constexpr int kMaxRobotJoints = 2000;
constexpr int kMaxRobotClosures = 2000;

// A visual mesh of a link (URDF <visual><geometry><mesh>, SDFormat <visual>).
struct RobotMesh {
  std::string file;          // absolute path of the mesh file (resolved by the reader)
  Eigen::Isometry3d X_WM = Eigen::Isometry3d::Identity();  // mesh frame in W, zero configuration
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

struct RobotLink {
  std::string name;
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();  // link frame in W, zero configuration
  // <inertial>: mass [kg], centre of mass in W [m] and the inertia about it
  // in W's axes [kg m^2], at the zero configuration (mass 0: none given).
  double mass = 0;
  Eigen::Vector3d com_W = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_W = Eigen::Matrix3d::Zero();
  std::vector<RobotMesh> meshes;
  int line = 0;  // source line of the link element (0: unknown)
};

// kPlanar and kFloating join the ground to a mobile base: a wheeled one, and
// a legged one (a floating joint with ccma's extension, formats/internal/legged_extension.h).
enum class RobotJointType { kRevolute, kPrismatic, kFixed, kSpherical, kUniversal, kPlanar, kFloating };

struct RobotJoint {
  std::string name;
  RobotJointType type = RobotJointType::kFixed;
  std::string parent, child;  // link names; kRobotWorld for the ground
  // The joint frame in W at the zero configuration (URDF: the child link's
  // frame; SDFormat: the joint's pose). Its origin is the joint point.
  Eigen::Isometry3d X_WJ = Eigen::Isometry3d::Identity();
  // Unit axis in W: revolute and prismatic (motion of the child relative to
  // the parent, right-handed), planar (the plane's normal), universal (the
  // axis fixed in the parent).
  Eigen::Vector3d axis_W = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d axis2_W = Eigen::Vector3d::UnitX();  // universal: axis fixed in the child
  bool limited = false;
  double lower = 0, upper = 0;  // rad or m, when limited
  // The joint coordinate in the configuration the link poses describe
  // (URDF: 0; SDFormat: <initial_position> where given), rad or m.
  double position = 0;
  // kFloating: the legged base's body its extension element describes.
  LeggedBody legged;
  int line = 0;
};

// Two frames that the closure makes coincide: the origins (3d), or the
// whole frames (6d). Each frame is fixed in a link.
struct RobotClosure {
  std::string frame_a, frame_b;  // as named in the source (link or joint names)
  std::string link_a, link_b;    // the links carrying them (kRobotWorld allowed)
  Eigen::Isometry3d X_WA = Eigen::Isometry3d::Identity();  // frame A in W, zero configuration
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();  // frame B in W, zero configuration
  bool six_d = true;             // false: 3d (origins only)
  int line = 0;                  // line in the closure file (or SDFormat file)
  std::string name;              // the closing joint's name; "" for frame_a__frame_b
};

// The name of the joint a closure becomes (before ccma's name cleaning).
inline std::string ClosureJointName(const RobotClosure& c) {
  return c.name.empty() ? c.frame_a + "__" + c.frame_b : c.name;
}

// An end-effector stored in the source by `ccma export` (optional).
struct RobotEndEffector {
  std::string link;
  Eigen::Vector3d point_L = Eigen::Vector3d::Zero();  // in the link frame, m
  std::vector<std::string> controlled;                 // x y z roll pitch yaw
};

struct RobotDescription {
  std::string name;    // the robot's name ([A-Za-z0-9_-] only; the reader cleans it)
  std::string source;  // the file read (for messages)
  std::vector<RobotLink> links;    // source order
  std::vector<RobotJoint> joints;  // source order
  std::vector<RobotClosure> closures;
  std::vector<std::string> actuated;  // joint names, in control order
  bool has_end_effector = false;
  RobotEndEffector end_effector;
  // Gravity in W [m/s^2], when the source gives it (an SDFormat world's
  // <gravity>); else the model's default.
  bool has_gravity = false;
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
  // What the reader skipped, one line each ("file:line: key: what"); the
  // command prints them on stderr.
  std::vector<std::string> warnings;

  int FindLink(const std::string& link_name) const {
    for (int i = 0; i < static_cast<int>(links.size()); ++i) {
      if (links[i].name == link_name) return i;
    }
    return -1;
  }
  int FindJoint(const std::string& joint_name) const {
    for (int i = 0; i < static_cast<int>(joints.size()); ++i) {
      if (joints[i].name == joint_name) return i;
    }
    return -1;
  }
};

}  // namespace ccma

#endif  // CCMA_FORMATS_ROBOT_DESCRIPTION_H_
