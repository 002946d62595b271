#include "formats/internal/root_weld.h"

#include <set>

#include "ccma/internal/format.h"

namespace ccma::internal {

void WeldTheRoot(const std::string& model_name, RobotDescription* robot) {
  std::set<std::string> children, names;
  for (const RobotJoint& joint : robot->joints) {
    if (joint.parent == kRobotWorld) return;
    children.insert(joint.child);
    names.insert(joint.name);
  }
  for (const RobotLink& link : robot->links) {
    if (children.count(link.name) != 0) continue;
    RobotJoint weld;
    weld.name = std::string(kRobotWorld) + "__" + link.name;
    while (names.count(weld.name) != 0) weld.name += "_";
    weld.parent = kRobotWorld;
    weld.child = link.name;
    weld.X_WJ = link.X_WL;
    weld.line = link.line;
    robot->joints.push_back(weld);
    robot->warnings.push_back("model " + Quote(model_name) + " has no joint to world: its root link " +
                              Quote(link.name) + " is welded to world where it is posed (joint " +
                              Quote(weld.name) + "), as a URDF's root is");
    return;
  }
}

}  // namespace ccma::internal
