// MuJoCo MJCF files as robots ccma imports (`ccma import --from=FILE.xml` with
// a <mujoco> root; contract: model_format.md, "MuJoCo MJCF"), read through
// MuJoCo's own compiler (Debian's libmujoco 2.2.2) after ccma's XML checks:
//  * refused before MuJoCo sees the file: what robot_xml.h refuses (size,
//    nesting, DOCTYPE ...), <include> and any element with a `file`
//    attribute (MuJoCo would open the files they name: an imported file
//    never makes ccma open another), tendons, and joint, tendon and
//    distance equalities (ccma has none of them), each named with its line;
//  * MuJoCo compiles the text from memory (a virtual file: it opens nothing);
//    its errors come back as the file's;
//  * the configuration read: the keyframe `keyframe` names, else qpos0;
//  * every body a link at its pose there (MuJoCo's forward kinematics), its
//    mass, centre of mass and inertia as MuJoCo compiled them (from the
//    geoms when the file gives no <inertial>); a body with no joint is
//    welded to its parent, one with several joints becomes a chain of
//    massless links BODY__JOINT, one per joint but the last, except a
//    mobile base: a body of the world whose joints are slide x, slide y,
//    hinge z (world axes, as ccma export writes a base) is a planar base
//    (joint BODY_planar); a root's free joint is welded where it is (said),
//    a free joint inside the tree refused;
//  * hinge -> revolute, slide -> prismatic (position: the joint's qpos, so
//    ccma's q is MuJoCo's qpos), ball -> spherical; `range` when limited;
//  * connect -> a 3d closure at its two anchors, weld -> a 6d closure (body2
//    at its anchor held at the relative pose in body1), each named after the
//    equality (inactive ones skipped, said);
//  * actuators on joints -> the actuated joints in actuator order (`actuated`
//    replaces them); a site named `end_effector` -> the stored end-effector;
//  * gravity from <option>.
#ifndef CCMA_FORMATS_MJCF_READER_H_
#define CCMA_FORMATS_MJCF_READER_H_

#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma {

struct MjcfReadOptions {
  std::vector<std::string> actuated;  // joint names; empty: the actuators' joints
  std::string keyframe;               // "" for qpos0
};

// Throws ModelError "path:LINE: what" for what ccma refuses, "path: MuJoCo:
// what" for what MuJoCo's compiler refuses, and for an unknown keyframe.
RobotDescription ReadMjcf(const std::string& path, const MjcfReadOptions& options);
// The same for text in memory, named `path` in messages.
RobotDescription ReadMjcfFromString(const std::string& text, const std::string& path, const MjcfReadOptions& options);

// Whether `text` (an XML document) has a <mujoco> root element: the sniff
// that tells an MJCF .xml from a URDF one.
bool HasMjcfRoot(const std::string& text);

}  // namespace ccma

#endif  // CCMA_FORMATS_MJCF_READER_H_
