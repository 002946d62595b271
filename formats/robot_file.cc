#include "formats/robot_file.h"

#include <stdexcept>

#include "formats/sdformat_reader.h"
#include "formats/urdf_reader.h"

namespace ccma {
namespace {

bool EndsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

RobotFileFormat RobotFileFormatOf(const std::string& path) {
  if (EndsWith(path, ".sdf") || EndsWith(path, ".world")) return RobotFileFormat::kSdformat;
  if (EndsWith(path, ".urdf") || EndsWith(path, ".xml")) return RobotFileFormat::kUrdf;
  return RobotFileFormat::kUnknown;
}

RobotDescription ReadRobotFile(const std::string& path, RobotFileFormat format, const std::string& closures_path,
                               const std::vector<std::string>& actuated) {
  switch (format) {
    case RobotFileFormat::kUrdf:
      return ReadUrdf(path, closures_path);
    case RobotFileFormat::kSdformat:
      if (!closures_path.empty()) throw std::invalid_argument("closures is for URDF (SDFormat holds its loops)");
      return ReadSdformat(path, actuated);
    case RobotFileFormat::kUnknown:
      break;
  }
  throw std::invalid_argument("the robot file must be a .urdf, .xml, .sdf or .world file");
}

}  // namespace ccma
