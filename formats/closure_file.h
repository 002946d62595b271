// The closure file that accompanies a URDF: the convention of the public
// example-parallel-robots collection (LAAS-CNRS/INRIA), YAML:
//   closed_loop: [[A, B], ...]     pairs of frame names (link or joint names)
//   type: ['6d' | '3d', ...]       6d: the frames coincide; 3d: their origins do
//   name_mot: [joint, ...]         the actuated joints
//   joint_name: [joint, ...]       optional: joints whose type is replaced by
//   joint_type: [SPHERICAL | FIXED | UJOINT_XY | UJOINT_YZ | UJOINT_ZX | UJOINT_ZY, ...]
// plus ccma's own optional keys:
//   offset: [[x, y, z, roll, pitch, yaw] | null, ...]   per pair: where the
//                                  closing point lies in the pair's first
//                                  frame (m, rad; R = Rz Ry Rx): that frame
//                                  moved by its offset is joined to the
//                                  second (null or missing: identity)
// and, written by `ccma export`:
//   end_effector: {link, point, controlled}
//   q_home: {joint: q, ...}        the joint positions (rad or m) at which the
//                                  URDF's links are read: the model's home,
//                                  where the loops are closed
//   frames: [link, ...]            links that are frames, not bodies: each is
//                                  fused into the link it is welded to
//                                  (formats/internal/frame_links.h)
// Other keys are ignored.
#ifndef CCMA_FORMATS_CLOSURE_FILE_H_
#define CCMA_FORMATS_CLOSURE_FILE_H_

#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma {

struct ClosureFile {
  struct Loop {
    std::string frame_a, frame_b;
    bool six_d = true;
    // `offset`: the joined frame in frame A (identity when none is given).
    Eigen::Isometry3d X_A_offset = Eigen::Isometry3d::Identity();
    int line = 0;
  };
  struct Override {
    std::string joint;
    std::string type;  // SPHERICAL, FIXED, UJOINT_XY, ...
    int line = 0;
  };
  struct Position {
    std::string joint;
    double q = 0;  // rad (revolute) or m (prismatic)
    int line = 0;
  };
  std::string source;  // the file read
  std::vector<Loop> loops;
  std::vector<std::string> actuated;  // name_mot
  int actuated_line = 0;
  std::vector<Override> overrides;
  std::vector<Position> positions;  // q_home, file order
  std::vector<std::string> frames;  // links to fuse into their bodies
  int frames_line = 0;
  bool has_end_effector = false;
  RobotEndEffector end_effector;
};

// Reads and checks the closure file at `path` (bounded size, names bounded,
// lists of equal length). Throws ModelError "path:line: key: what".
ClosureFile ReadClosureFile(const std::string& path);
// The same for text in memory; `source` names it in messages.
ClosureFile ParseClosureFile(const std::string& text, const std::string& source);

// Adds the file's closures, type overrides, actuated joints and end-effector
// to `robot` (read from its URDF at its zero configuration), and moves its
// links to the `q_home` joint positions (formats/internal/joint_positions.h)
// before the closures' frames are taken, then fuses the `frames` links into
// their bodies (formats/internal/frame_links.h). A frame name is a link name, or a
// joint name standing for its child link's frame. Throws ModelError
// "closures.yaml:LINE: closed_loop[i]: unknown frame 'X' (no link or joint of
// robot.urdf has that name)" and likewise for unknown joints; a q_home
// joint that is not revolute or prismatic (after the joint_type overrides).
void ApplyClosureFile(const ClosureFile& file, RobotDescription* robot);

}  // namespace ccma

#endif  // CCMA_FORMATS_CLOSURE_FILE_H_
