// SDFormat (1.7 or later; joints may form loops) -> RobotDescription.
#ifndef CCMA_FORMATS_SDFORMAT_READER_H_
#define CCMA_FORMATS_SDFORMAT_READER_H_

#include <string>
#include <vector>

#include "formats/robot_description.h"

namespace ccma {

// Reads the first model of the SDFormat file at `path`; `actuated` names its
// actuated joints. Throws ModelError with libsdformat's first errors.
RobotDescription ReadSdformat(const std::string& path, const std::vector<std::string>& actuated);

}  // namespace ccma

#endif  // CCMA_FORMATS_SDFORMAT_READER_H_
