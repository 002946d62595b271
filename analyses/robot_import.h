// A robot read from URDF or SDFormat (formats/robot_description.h) -> a ccma
// Model assembled at home (`ccma import`, docs/import.md).
//
// Mapping: every link becomes a body of the same name (frame = link frame);
// every joint keeps its name and type; a planar joint from the ground makes
// its link an omni mobile base; a closure becomes a fixed (6d) or spherical
// (3d) joint named A__B. Names are mapped to ccma names ([A-Za-z0-9_-], at
// most 64 characters; other characters become '_').
//
// Home: the source's zero configuration, assembled by the forward solver with
// the actuated joints held at their source value (when the loops cannot be
// closed so, with the motors free, and a warning); every revolute and
// prismatic joint gets q_home = its source joint position there, so every q
// ccma reports is the source's joint position.
//
// Controlled components: the given ones (ImportOptions), refused when the
// controls cannot move them independently at home; else the ones the source
// stores (ccma export: the exported model's own, kept, with a warning when
// the controls cannot move them); else those the controls move at home
// (analyses/moved_components.h): a planar five-bar gets its two in-plane
// translations.
#ifndef CCMA_ANALYSES_ROBOT_IMPORT_H_
#define CCMA_ANALYSES_ROBOT_IMPORT_H_

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ccma/model.h"
#include "formats/robot_description.h"

namespace ccma {

struct ImportOptions {
  // Actuated joints (planar ones are mobile bases); empty: the source's.
  std::vector<std::string> actuated;
  // End-effector link; empty: the one stored in the source (ccma export),
  // else an error.
  std::string end_effector_link;
  Eigen::Vector3d end_effector_point_L = Eigen::Vector3d::Zero();  // in the link frame [m]
  // Controlled components (x y z roll pitch yaw); empty: the ones stored in
  // the source (ccma export), else the ones the controls move at home,
  // chosen translations first (analyses/moved_components.h).
  std::vector<std::string> controlled;
  std::string model_name;  // name of the written model; empty: the robot's
  // The folder the model file will be written to: mesh paths are written
  // relative to it (analyses/internal/import_mesh_paths.h), so that the model
  // and its meshes can be moved together. Empty: the robot file's folder,
  // against which ImportedRobot::model's source also resolves them.
  std::string model_folder;
  // > 0: every body that is not a mobile base gets capsules of this radius
  // [m] along the segments between its joint points, and pairs closer than
  // the margin at home are ignored (analyses/internal/import_collision.h);
  // 0: no collision geometry (robot files give meshes, which clearance does
  // not use).
  double collision_radius = 0;
  // Refuse (ModelError) an import that closes a gap between a closure's
  // frames or moves a motor from its source position by more than
  // kImportTolerance: the file then describes another mechanism than the
  // one written.
  bool strict = false;

  // Names non-empty and at most kMaxImportNameBytes, the point finite and
  // within 1e4 m, collision_radius 0 or in [1e-4, 10] m. `why` names the
  // option as Python's import_robot() does ("collision_radius: ...").
  bool IsValid(std::string* why) const;
};

// The longest joint or link name an import is asked for [bytes].
constexpr std::size_t kMaxImportNameBytes = 256;

// A gap or a motor move beyond this [m or rad] is named (and refused with
// ImportOptions::strict).
constexpr double kImportTolerance = 1e-6;

// How far a closure's two frames are apart at the source's joint positions.
struct ClosureGap {
  std::string name;   // the closing joint's name in the model (A__B)
  double gap_m = 0;   // distance between the origins [m]
  double gap_rad = 0; // angle between the frames [rad] (6d closures; 0 for 3d)
};

// How far assembling at home moved an actuated joint from its source position.
struct MotorMove {
  std::string name;
  double move = 0;  // [rad or m], home minus source (revolute: wrapped into (-pi, pi])
};

struct ImportedRobot {
  Model model;          // as loaded back from `yaml` (validated by the loader); mesh paths
                        // relative to ImportOptions::model_folder
  std::string yaml;     // the model file text
  double residual_energy = 0;  // E at home of `model` [m^2]
  int closures = 0;  // independent loops (joints + bases - bodies)
  std::vector<std::string> actuated;  // ccma names, in control order (bases first)
  std::vector<std::string> controlled;  // the model's controlled components, x y z roll pitch yaw order
  bool controlled_chosen = false;       // true when ImportRobot chose them (none given or stored)
  std::vector<std::string> warnings;  // e.g. the motors had to move to close the loops
  int collision_capsules = 0;       // with collision_radius: capsules written
  int collision_ignored_pairs = 0;  // with collision_radius: body pairs touching at home, ignored
  std::vector<ClosureGap> closure_gaps;  // every closure of the description, in its order
  std::vector<MotorMove> motor_moves;    // every actuated revolute or prismatic joint, in model order
};

// Throws ModelError naming the source, the element and the name: an unknown
// actuated joint or end-effector link, a joint type that cannot be actuated,
// a link connected to neither the ground nor a base, a closure that cannot
// be assembled (its residual), a joint whose assembled position lies outside
// its limits, controlled components the controls cannot move independently
// at home (naming the ones they move), an end-effector the controls do not
// move at all (unless the source stores its components). Throws
// std::invalid_argument, before any work, for options that are not IsValid.
ImportedRobot ImportRobot(const RobotDescription& robot, const ImportOptions& options);

}  // namespace ccma

#endif  // CCMA_ANALYSES_ROBOT_IMPORT_H_
