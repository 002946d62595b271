#include "formats/robot_file.h"

#include <stdexcept>

#include "formats/closure_file.h"
#include "formats/mjcf_reader.h"
#include "formats/model_loader.h"
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
                               const std::vector<std::string>& actuated, const std::string& keyframe) {
  if (!keyframe.empty() && format == RobotFileFormat::kSdformat) {
    throw std::invalid_argument("keyframe is for MuJoCo MJCF files");
  }
  switch (format) {
    case RobotFileFormat::kUrdf: {
      if (!EndsWith(path, ".xml")) {
        if (!keyframe.empty()) throw std::invalid_argument("keyframe is for MuJoCo MJCF files");
        return ReadUrdf(path, closures_path);
      }
      // An .xml: MJCF when its root is <mujoco>, else URDF.
      std::string text, error;
      if (!internal::ReadRegularFile(path, kMaxRobotFileBytes, "robot file", &text, &error)) throw ModelError(error);
      if (HasMjcfRoot(text)) {
        if (!closures_path.empty()) throw std::invalid_argument("closures is for URDF (MJCF holds its loops)");
        return ReadMjcfFromString(text, path, MjcfReadOptions{actuated, keyframe});
      }
      if (!keyframe.empty()) throw std::invalid_argument("keyframe is for MuJoCo MJCF files");
      RobotDescription robot = ReadUrdfFromString(text, path);
      if (!closures_path.empty()) ApplyClosureFile(ReadClosureFile(closures_path), &robot);
      return robot;
    }
    case RobotFileFormat::kSdformat:
      if (!closures_path.empty()) throw std::invalid_argument("closures is for URDF (SDFormat holds its loops)");
      return ReadSdformat(path, actuated);
    case RobotFileFormat::kUnknown:
      break;
  }
  throw std::invalid_argument("the robot file must be a .urdf, .xml, .sdf or .world file");
}

}  // namespace ccma
