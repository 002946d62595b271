#include "formats/sdformat_reader.h"

#include "formats/model_loader.h"

namespace ccma {

RobotDescription ReadSdformat(const std::string& path, const std::vector<std::string>& /*actuated*/) {
  throw ModelError(path + ": SDFormat import is not available in this build");
}

}  // namespace ccma
