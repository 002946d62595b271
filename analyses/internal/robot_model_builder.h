// Step one of ImportRobot (analyses/robot_import.h): the robot as a Model
// whose home is the source's configuration, closures not yet closed (their
// two frames keep their own points and orientations in their bodies).
#ifndef CCMA_ANALYSES_INTERNAL_ROBOT_MODEL_BUILDER_H_
#define CCMA_ANALYSES_INTERNAL_ROBOT_MODEL_BUILDER_H_

#include <string>
#include <vector>

#include "analyses/robot_import.h"
#include "ccma/model.h"
#include "formats/robot_description.h"

namespace ccma {
namespace internal {

struct RobotModel {
  Model model;                   // bodies: links then bases; joints: tree, then closures
  std::vector<bool> closure;     // per joint of `model`
  std::vector<std::string> actuated;  // ccma names in control order
  // Where model.end_effector.controlled comes from: ImportOptions, the
  // source (ccma export stores it), or neither (it holds all six and
  // ImportRobot chooses).
  enum class Controlled { kGiven, kStored, kToChoose };
  Controlled controlled = Controlled::kToChoose;
};

// Throws ModelError as ImportRobot documents.
RobotModel BuildRobotModel(const RobotDescription& robot, const ImportOptions& options);

// `name` made a ccma name: characters outside [A-Za-z0-9_-] become '_',
// at most kMaxNameLength characters (ccma/limits.h), never empty.
std::string CcmaName(const std::string& name);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_ROBOT_MODEL_BUILDER_H_
