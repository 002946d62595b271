// What an import changed to close the loops (analyses/robot_import.h
// ImportedRobot::closure_gaps, motor_moves): how far apart each closure's
// frames are in the source, and how far assembling moved each motor.
#ifndef CCMA_ANALYSES_INTERNAL_IMPORT_REPORT_H_
#define CCMA_ANALYSES_INTERNAL_IMPORT_REPORT_H_

#include <string>
#include <vector>

#include "analyses/robot_import.h"

namespace ccma::internal {

// Every closure of `robot` at the source's joint positions: first the
// source's own loop-closing joints (SDFormat's, a URDF's Gazebo <joint>s:
// those a spanning tree in file order leaves out, gap 0 since each is posed
// once), then the closure file's, named as the model's closing joint (A__B):
// the origins' distance [m] and, for a 6d closure, the angle between the
// frames [rad]. As many as the import's `closures`.
std::vector<ClosureGap> ClosureGaps(const RobotDescription& robot);

// Every actuated revolute or prismatic joint: its home position in `home`
// less its source position in `source` (the same joints, in order).
std::vector<MotorMove> MotorMoves(const Model& source, const Model& home);

// One line per gap or move beyond kImportTolerance, naming it and its size
// ("closure 'a__b': its frames are 0.2 m and 0 rad apart in the source").
std::vector<std::string> ImportChanges(const std::vector<ClosureGap>& gaps, const std::vector<MotorMove>& moves);

}  // namespace ccma::internal

#endif  // CCMA_ANALYSES_INTERNAL_IMPORT_REPORT_H_
