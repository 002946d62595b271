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

#include "ccma/base_kind.h"
#include "ccma/collision_geometry.h"
#include "ccma/mass_properties.h"
#include "ccma/omni_wheels.h"
#include "ccma/stiffness.h"

namespace ccma {

// The ground as a joint end (`world` in model files): identity pose, never
// moves, not part of the state.
constexpr int kWorld = -1;

enum class JointType { kRevolute, kSpherical, kUniversal, kPrismatic, kFixed };
enum class Actuation { kComplete, kReduced };
// omni: holonomic (moves in any direction); differential: two driven wheels
// on one axle, moves along its heading and turns; legged: a quadruped that
// also raises, lowers and tilts its body (docs/model_format.md). Each type's
// controls and constraints: ccma/base_kind.h, ccma/bases/.
enum class BaseType { kOmni, kDifferential, kLegged };

// "revolute", "spherical", ... (the model-file spelling).
const char* JointTypeName(JointType type);

// Number of constraint rows a joint contributes (read from its cost
// function, cost_functions/*_cost.h, where each size is stated once).
int JointResidualCount(JointType type);
struct Joint;
// Constraint rows of a joint's motor (0 unless actuated).
int ActuatorResidualCount(const Joint& joint);
// The directions a joint of this type does not allow, translations and
// rotations (ccma/stiffness.h): one stiffness value each.
int TranslationSpringCount(JointType type);
int RotationSpringCount(JointType type);

// A visual mesh fixed in a body (the `meshes:` key of bodies and bases),
// drawn by `ccma view --meshes`; no other tool reads it.
struct BodyMesh {
  std::string file;  // as written in the model file: absolute, or relative to its folder
  Eigen::Matrix3d R_BM = Eigen::Matrix3d::Identity();  // mesh frame in the body frame
  Eigen::Vector3d p_BM = Eigen::Vector3d::Zero();      // m
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();     // per mesh axis (STL units to m)
  int line = 0;  // source line (for messages)
};

// A rigid body; mobile bases are bodies too (is_mobile_base).
struct Body {
  std::string name;
  std::vector<BodyMesh> meshes;  // visual only; empty unless the file names some
  Eigen::Matrix3d R_WB_home = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_WB_home = Eigen::Vector3d::Zero();
  int base_index = -1;  // index into Model::mobile_bases, or -1
  MassProperties inertia;  // `mass`, `com` (statics only)
  bool is_mobile_base() const { return base_index >= 0; }
};

// A differential-drive base's two wheels.
struct DifferentialWheels {
  double track = 0.3;    // m, distance between the wheels
  double radius = 0.05;  // m
};

// A legged base's body (`body_height`, `body_limits`, `footprint`).
struct LeggedBody {
  double height = 0;  // m, home height of the body frame above the floor
  // Limits of the height [m], roll and pitch [rad] controls (`body_limits`).
  ControlRange height_limits, roll_limits, pitch_limits;
  // Collision box: length along the heading, width [m]; 0 when not given.
  Eigen::Vector2d footprint = Eigen::Vector2d::Zero();
};

// A mobile base: an actuator. Its controls are the block of u from
// Model::base_control(k) on: x [m], y [m], heading [rad] of its body frame on
// the floor, then its type's further controls (ccma/base_kind.h).
struct MobileBase {
  std::string name;
  int body = -1;  // index into Model::bodies
  BaseType type = BaseType::kOmni;
  Actuation actuation = Actuation::kComplete;  // differential: always complete
  Eigen::Vector3d home_pose = Eigen::Vector3d::Zero();  // x, y, theta
  // Its wheels (optional `wheels:` block; omni default: DefaultWheels()).
  // Only the base-driving layer (base_tracking.h) uses them.
  std::vector<Wheel> wheels = DefaultWheels();
  DifferentialWheels differential;  // type kDifferential only
  LeggedBody legged;                 // type kLegged only
  // The largest horizontal force the base can exert [N] (`push_limit`);
  // 0: not given.
  double push_limit = 0;
  // How fast `ccma retime` may drive it (`velocity_limit`): empty, or
  // [V m/s over the floor, W rad/s turn rate] (a legged base adds its
  // height, roll and pitch rates: [V, W, Vz m/s, Wr rad/s, Wp rad/s]).
  std::vector<double> velocity_limit;
  // Its `stiffness` (ccma/stiffness.h); rigid when not given.
  BaseStiffness stiffness;
};

// A joint of the passive chain between bodies A and B (file order of
// `between`). Geometry is given in the frame of the body named in the suffix.
struct Joint {
  std::string name;  // given, or "joint<i>" (i: index in the file's list)
  JointType type = JointType::kSpherical;
  int body_a = kWorld, body_b = kWorld;  // body indices, or kWorld
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
  // revolute: a reference direction perpendicular to the axis (the same
  // world direction at home) in A (e1_A, with e2_A = a_A x e1_A) and in B
  // (w_B); the joint coordinate q = atan2(e2 . w, e1 . w) (joint_coordinates.h).
  Eigen::Vector3d e1_A = Eigen::Vector3d::UnitX(), e2_A = Eigen::Vector3d::UnitY();
  Eigen::Vector3d w_B = Eigen::Vector3d::UnitX();
  // revolute, prismatic: the value of q at home [rad or m] (`q_home`,
  // default 0). Every reported q is q_home plus the motion since home.
  double q_home = 0.0;
  // revolute, prismatic: the joint coordinate q is a control (its motor
  // holds it at u[control]); home value q_home.
  bool actuated = false;
  int control = -1;  // index into u when actuated
  // revolute, prismatic: lower <= q <= upper (rad or m, the same coordinate
  // as q, so lower <= q_home <= upper) when `limited`.
  bool limited = false;
  double lower = 0, upper = 0;
  // Actuated joints: the range of the motor's effort (`effort_limits`).
  EffortLimits effort;
  // Actuated joints: the largest |q'| `ccma retime` may drive [rad/s or m/s]
  // (`velocity_limit`); 0: not given.
  double velocity_limit = 0;
  // Its `stiffness` (ccma/stiffness.h); rigid when not given.
  JointStiffness stiffness;
  int line = 0;  // source line in the model file (for messages)

  // Revolute and prismatic joints have a coordinate q.
  bool has_coordinate() const { return type == JointType::kRevolute || type == JointType::kPrismatic; }
};

// The controlled components of X_EE, in this order.
enum EndEffectorComponent { kX = 0, kY, kZ, kRoll, kPitch, kYaw };
extern const std::array<const char*, 6> kEndEffectorComponentNames;

struct EndEffector {
  int body = -1;
  Eigen::Vector3d p_B = Eigen::Vector3d::Zero();       // point in body frame
  Eigen::Vector3d p_W_home = Eigen::Vector3d::Zero();  // the same, world, home
  std::array<bool, 6> controlled{};                    // x y z roll pitch yaw
  MassProperties payload;  // carried by `body` (`payload`; statics only)
};

struct Model {
  std::string name;
  std::string description;
  std::string source;  // file it was loaded from ("" if built in code)
  std::vector<Body> bodies;  // file order: `bodies` first, then mobile bases
  std::vector<MobileBase> mobile_bases;
  std::vector<Joint> joints;
  EndEffector end_effector;
  // Shapes kept apart by control (collision_geometry.h); disabled unless the
  // file has `collision:` or `obstacles:`.
  CollisionGeometry collision;
  // Gravity in the world frame [m/s^2] (`gravity`; statics only).
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);

  int num_bodies() const { return static_cast<int>(bodies.size()); }
  int num_bases() const { return static_cast<int>(mobile_bases.size()); }
  // 6 numbers per body: orientation increment (3, rad) then translation (3, m).
  int state_size() const { return 6 * num_bodies(); }
  // Actuated joints (one control each), in file order.
  int num_actuated_joints() const;
  // Each base's controls (3, or 6 for a legged base), then one per actuated
  // joint (q).
  int num_controls() const { return num_base_controls() + num_actuated_joints(); }
  // The bases' controls together; the actuated joints' follow them in u.
  int num_base_controls() const;
  // Index into u of base k's first control (its x).
  int base_control(int k) const;
  // Indices into u of the controls the control solver may change
  // (x, y of every base; theta of complete ones; every actuated joint).
  std::vector<int> effective_control_indices() const;
  // The index of the joint with this name, or -1.
  int FindJoint(const std::string& name) const;
  // Total number of constraint rows (joints and bases).
  int num_constraints() const;
  // The controls at home: the bases' poses in file order, then q_home per
  // actuated joint.
  Eigen::VectorXd home_controls() const;
  // Index of the body with this name, or -1.
  int FindBody(const std::string& name) const;
  // Whether any base or joint has a `stiffness` (the mechanism is compliant).
  bool compliant() const;
};

}  // namespace ccma

#endif  // CCMA_MODEL_H_
