// The name of a model that `ccma import` writes (docs/import.md, "Model
// name"): the name the file gives the robot (URDF <robot name>, SDFormat
// <model name>), unless it is empty or a name that exporters give every
// robot (onshape-to-robot writes "onshape"), then the file's stem, then the
// name of the file's folder (example-parallel-robots keeps each robot as
// robot.urdf in a folder named after it).
#ifndef CCMA_ANALYSES_INTERNAL_IMPORT_MODEL_NAME_H_
#define CCMA_ANALYSES_INTERNAL_IMPORT_MODEL_NAME_H_

#include <string>

#include "formats/robot_description.h"

namespace ccma {
namespace internal {

// Whether `name` says nothing of the robot: empty, or (case aside) one of
// "onshape", "robot", "model", "default", "untitled".
bool IsGenericRobotName(const std::string& name);

// The first of the robot's name, the stem of robot.source and the name of
// its folder that is not generic, made a ccma name (CcmaName: characters
// outside [A-Za-z0-9_-] become '_', at most 64); when all are generic, the
// robot's name if it has one, else "robot".
std::string ImportedModelName(const RobotDescription& robot);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_ANALYSES_INTERNAL_IMPORT_MODEL_NAME_H_
