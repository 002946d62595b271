// What the robot-file fuzz targets (SDFormat, MJCF) do with a description a
// reader accepted: check it names its source, import it when it is small
// (assembling a large robot is the solver's business, not theirs), and
// check what comes out. A failure is a bug (fuzz_checks.h).
#ifndef CCMA_FUZZ_ROBOT_IMPORT_FUZZ_H_
#define CCMA_FUZZ_ROBOT_IMPORT_FUZZ_H_

#include <cstddef>
#include <string>

#include "analyses/robot_import.h"
#include "formats/robot_description.h"
#include "fuzz/fuzz_checks.h"

namespace ccma_fuzz {

constexpr std::size_t kMaxImportedLinks = 30;

inline void ImportWhatWasRead(const ccma::RobotDescription& robot, const std::string& source) {
  if (robot.source != source) Fail("wrong source", robot.source);
  if (robot.links.size() > kMaxImportedLinks) return;
  ccma::ImportOptions options;
  if (!robot.has_end_effector && !robot.links.empty()) options.end_effector_link = robot.links.back().name;
  const ccma::ImportedRobot imported = ccma::ImportRobot(robot, options);
  if (imported.model.num_bodies() == 0) Fail("imported a model without bodies", imported.yaml);
}

}  // namespace ccma_fuzz

#endif  // CCMA_FUZZ_ROBOT_IMPORT_FUZZ_H_
