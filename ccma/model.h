// The CCMA model: a constant description of rigid bodies, mobile bases, the
// joints of the passive chain and the end-effector. Loaded once (see
// model_loader.h), then shared read-only by every problem built on it.
//
// Frames: W = world (z up, ground z = 0); each body B has a frame whose home
// pose (R_WB_home, p_WB_home) comes from the model file. Joint geometry is
// stored in each body's own frame, so constraints are exactly zero at home.
// Units: metres, radians.
#ifndef CCMA_MODEL_H_
#define CCMA_MODEL_H_

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/omni_wheels.h"

namespace ccma {

// Controls per mobile base: x [m], y [m], theta [rad].
constexpr int kBaseControlSize = 3;

enum class JointType { kRevolute, kSpherical, kUniversal, kPrismatic, kFixed };
enum class Actuation { kComplete, kReduced };

// "revolute", "spherical", ... (the model-file spelling).
const char* JointTypeName(JointType type);

// Number of constraint rows a joint contributes (read from its cost
// function, cost_functions/*_cost.h, where each size is stated once).
int JointResidualCount(JointType type);
// Constraint rows of one mobile base (planar and motor).
int BaseResidualCount();

// A rigid body; mobile bases are bodies too (is_mobile_base).
struct Body {
  std::string name;
  Eigen::Matrix3d R_WB_home = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_WB_home = Eigen::Vector3d::Zero();
  int base_index = -1;  // index into Model::mobile_bases, or -1
  bool is_mobile_base() const { return base_index >= 0; }
};

// An omnidirectional mobile base: the actuator. Its controls are
// u[3k..3k+2] = (x [m], y [m], theta [rad]) of its body frame on the ground.
struct MobileBase {
  std::string name;
  int body = -1;  // index into Model::bodies
  Actuation actuation = Actuation::kComplete;
  Eigen::Vector3d home_pose = Eigen::Vector3d::Zero();  // x, y, theta
  // Its wheels (optional `wheels:` block; default: DefaultWheels()). Only
  // the base-driving layer (base_tracking.h) uses them.
  std::vector<Wheel> wheels = DefaultWheels();
};

// A joint of the passive chain between bodies A and B (file order of
// `between`). Geometry is given in the frame of the body named in the suffix.
struct Joint {
  JointType type = JointType::kSpherical;
  int body_a = -1, body_b = -1;
  Eigen::Vector3d p_A = Eigen::Vector3d::Zero();  // joint point in A
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();  // joint point in B
  // revolute, prismatic: unit axis in A and B. universal: axes[0] in A (a_A)
  // and axes[1] in B (b_B).
  Eigen::Vector3d a_A = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d a_B = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d b_B = Eigen::Vector3d::UnitX();
  // fixed, prismatic: two body-fixed reference directions (world x and y at
  // home) expressed in A and B; their difference locks relative rotation.
  Eigen::Vector3d d1_A, d1_B, d2_A, d2_B;
  int line = 0;  // source line in the model file (for messages)
};

// The controlled components of X_EE, in this order.
enum EndEffectorComponent { kX = 0, kY, kZ, kRoll, kPitch, kYaw };
extern const std::array<const char*, 6> kEndEffectorComponentNames;

struct EndEffector {
  int body = -1;
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();       // point in body frame
  Eigen::Vector3d p_W_home = Eigen::Vector3d::Zero();  // the same, world, home
  std::array<bool, 6> controlled{};                    // x y z roll pitch yaw
};

struct Model {
  std::string name;
  std::string description;
  std::string source;  // file it was loaded from ("" if built in code)
  std::vector<Body> bodies;  // file order: `bodies` first, then mobile bases
  std::vector<MobileBase> mobile_bases;
  std::vector<Joint> joints;
  EndEffector end_effector;

  int num_bodies() const { return static_cast<int>(bodies.size()); }
  int num_bases() const { return static_cast<int>(mobile_bases.size()); }
  // 6 numbers per body: orientation increment (3, rad) then translation (3, m).
  int state_size() const { return 6 * num_bodies(); }
  // 3 per mobile base: x, y, theta.
  int num_controls() const { return kBaseControlSize * num_bases(); }
  // Indices into u of the controls the control solver may change
  // (x, y of every base; theta of complete ones).
  std::vector<int> effective_control_indices() const;
  // Total number of constraint rows (joints + 9 per base).
  int num_constraints() const;
  // The controls at home: the bases' poses in file order.
  Eigen::VectorXd home_controls() const;
  // Index of the body with this name, or -1.
  int FindBody(const std::string& name) const;
};

}  // namespace ccma

#endif  // CCMA_MODEL_H_
