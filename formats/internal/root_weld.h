// The ground of a robot file that names none: a model with no joint to
// `world` (a Gazebo model gets one from the world file that places it, and
// an MJCF body tree hangs from <worldbody>) has its root welded to `world`
// where it is posed, as a URDF's root is, and the description says so.
#ifndef CCMA_FORMATS_INTERNAL_ROOT_WELD_H_
#define CCMA_FORMATS_INTERNAL_ROOT_WELD_H_

#include <string>

#include "formats/robot_description.h"

namespace ccma::internal {

// When no joint of `robot` has `world` as parent: adds a fixed joint
// `world__ROOT` from `world` to ROOT, the first link in file order that is no
// joint's child (or, when every link is some joint's child, a closed loop
// floating free: the first link, SDFormat's canonical link), at ROOT's
// frame, and a warning naming `model_name`, ROOT and the joint. Nothing
// otherwise (nor for a robot without links).
void WeldTheRoot(const std::string& model_name, RobotDescription* robot);

}  // namespace ccma::internal

#endif  // CCMA_FORMATS_INTERNAL_ROOT_WELD_H_
