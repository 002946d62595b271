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
  const RobotLink* root = nullptr;
  for (const RobotLink& link : robot->links) {
    if (children.count(link.name) == 0) {
      root = &link;
      break;
    }
  }
  if (root == nullptr && !robot->links.empty()) root = &robot->links.front();  // a loop with no root
  if (root == nullptr) return;
  RobotJoint weld;
  weld.name = std::string(kRobotWorld) + "__" + root->name;
  while (names.count(weld.name) != 0) weld.name += "_";
  weld.parent = kRobotWorld;
  weld.child = root->name;
  weld.X_WJ = root->X_WL;
  weld.line = root->line;
  robot->warnings.push_back("model " + Quote(model_name) + " has no joint to world: its " +
                            (children.count(root->name) != 0 ? "first link " : "root link ") + Quote(root->name) +
                            " is welded to world where it is posed (joint " + Quote(weld.name) + "), as a URDF's root is");
  robot->joints.push_back(weld);
}

}  // namespace ccma::internal
