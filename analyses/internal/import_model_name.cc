#include "analyses/internal/import_model_name.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "analyses/internal/robot_model_builder.h"

namespace ccma {
namespace internal {

bool IsGenericRobotName(const std::string& name) {
  static const std::array<const char*, 5> kGeneric = {"onshape", "robot", "model", "default", "untitled"};
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.empty() || std::find(kGeneric.begin(), kGeneric.end(), lower) != kGeneric.end();
}

std::string ImportedModelName(const RobotDescription& robot) {
  // The folder of a bare file name is the working directory's.
  std::error_code error;
  std::filesystem::path source = std::filesystem::absolute(robot.source, error);
  if (error) source = robot.source;
  const std::string candidates[] = {robot.name, source.stem().string(), source.parent_path().filename().string()};
  for (const std::string& candidate : candidates) {
    if (!IsGenericRobotName(candidate)) return CcmaName(candidate);
  }
  return CcmaName(robot.name.empty() ? "robot" : robot.name);
}

}  // namespace internal
}  // namespace ccma
