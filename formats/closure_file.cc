#include "formats/closure_file.h"

#include <set>
#include <string>

#include "ccma/internal/format.h"
#include "ccma/limits.h"
#include "ccma/model.h"
#include "ccma/rotation.h"
#include "formats/internal/library_message.h"
#include "formats/internal/yaml_checks.h"
#include "formats/internal/yaml_document.h"
#include "formats/model_loader.h"

namespace ccma {
namespace {

// A closure file is a few lines; this bounds hostile ones.
constexpr std::size_t kMaxClosureFileBytes = std::size_t{1} << 20;
constexpr std::size_t kMaxClosureEntries = kMaxRobotClosures;

// A frame or joint name as URDF writes it: any printable text without
// control characters, at most kMaxNameLength * 4 bytes (the importer maps
// it to a ccma name).
std::string SourceName(const internal::YamlReader& r, const YAML::Node& node, const std::string& path) {
  const std::string text = r.String(node, path);
  bool printable = text.size() <= 4 * kMaxNameLength;
  for (const unsigned char c : text) printable = printable && c >= 0x20 && c != 0x7f;
  if (!printable) r.Fail(node, path, "must be a name of at most " + std::to_string(4 * kMaxNameLength) +
                                         " printable characters");
  return text;
}

std::vector<std::string> Names(const internal::YamlReader& r, const YAML::Node& map, const std::string& key) {
  std::vector<std::string> names;
  if (!internal::YamlReader::Has(map, key)) return names;
  const YAML::Node list = r.Sequence(map[key], key, kMaxClosureEntries, "names");
  for (std::size_t i = 0; i < list.size(); ++i) names.push_back(SourceName(r, list[i], internal::Indexed(key, i)));
  return names;
}

void ReadLoops(const internal::YamlReader& r, const YAML::Node& root, ClosureFile* file) {
  if (!internal::YamlReader::Has(root, "closed_loop")) return;
  const YAML::Node loops = r.Sequence(root["closed_loop"], "closed_loop", kMaxClosureEntries, "closures");
  const std::vector<std::string> types = Names(r, root, "type");
  if (internal::YamlReader::Has(root, "type") && types.size() != loops.size()) {
    r.Fail(root["type"], "type", "must have one entry per closed_loop pair (" + std::to_string(loops.size()) + ")");
  }
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const std::string path = internal::Indexed("closed_loop", i);
    const YAML::Node pair = r.Sequence(loops[i], path);
    if (pair.size() != 2) r.Fail(loops[i], path, "must be a pair of frame names [A, B]");
    ClosureFile::Loop loop;
    loop.frame_a = SourceName(r, pair[0], path + "[0]");
    loop.frame_b = SourceName(r, pair[1], path + "[1]");
    loop.line = loops[i].Mark().line + 1;
    if (!types.empty()) {
      // The collection writes both cases (its loader reads "3d" and "3D").
      const std::string type = types[i] == "3D" ? "3d" : types[i] == "6D" ? "6d" : types[i];
      if (type != "6d" && type != "3d") {
        r.Fail(root["type"][i], internal::Indexed("type", i), "must be '6d' or '3d', got " + Quote(types[i]));
      }
      loop.six_d = type == "6d";
    }
    file->loops.push_back(loop);
  }
}

// ccma's `offset: [[x, y, z, roll, pitch, yaw] | null, ...]`, one per pair.
void ReadOffsets(const internal::YamlReader& r, const YAML::Node& root, ClosureFile* file) {
  if (!internal::YamlReader::Has(root, "offset")) return;
  const YAML::Node offsets = r.Sequence(root["offset"], "offset", kMaxClosureEntries, "offsets");
  if (offsets.size() != file->loops.size()) {
    r.Fail(root["offset"], "offset", "must have one entry per closed_loop pair (" + std::to_string(file->loops.size()) +
                                         "), each [x, y, z, roll, pitch, yaw] or null");
  }
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    if (offsets[i].IsNull()) continue;
    const std::string path = internal::Indexed("offset", i);
    const YAML::Node six = r.Sequence(offsets[i], path);
    if (six.size() != 6) r.Fail(offsets[i], path, "must be [x, y, z, roll, pitch, yaw] (m, rad) or null");
    Eigen::Vector3d p, rpy;
    for (int k = 0; k < 3; ++k) {
      p[k] = r.Number(six[k], path + "[" + std::to_string(k) + "]", "m");
      rpy[k] = r.Number(six[k + 3], path + "[" + std::to_string(k + 3) + "]", "rad");
    }
    Eigen::Isometry3d& X = file->loops[i].X_A_offset;
    X.linear() = RotationFromRpy(rpy);
    X.translation() = p;
  }
}

void ReadOverrides(const internal::YamlReader& r, const YAML::Node& root, ClosureFile* file) {
  const std::vector<std::string> joints = Names(r, root, "joint_name");
  const std::vector<std::string> types = Names(r, root, "joint_type");
  if (joints.size() != types.size()) {
    r.Fail(internal::YamlReader::Has(root, "joint_type") ? root["joint_type"] : root["joint_name"], "joint_type",
           "must have one entry per joint_name (" + std::to_string(joints.size()) + ")");
  }
  static const std::set<std::string> kTypes = {"SPHERICAL", "FIXED",     "UJOINT_XY",
                                               "UJOINT_YZ", "UJOINT_ZX", "UJOINT_ZY"};
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (kTypes.count(types[i]) == 0) {
      r.Fail(root["joint_type"][i], internal::Indexed("joint_type", i),
             "unknown joint type " + Quote(types[i]) +
                 " (SPHERICAL, FIXED, UJOINT_XY, UJOINT_YZ, UJOINT_ZX or UJOINT_ZY)");
    }
    file->overrides.push_back({joints[i], types[i], root["joint_name"][i].Mark().line + 1});
  }
}

void ReadEndEffector(const internal::YamlReader& r, const YAML::Node& root, ClosureFile* file) {
  if (!internal::YamlReader::Has(root, "end_effector")) return;
  const YAML::Node node = r.Map(root["end_effector"], "end_effector");
  r.CheckKeys(node, {"link", "point", "controlled"}, "end_effector");
  file->has_end_effector = true;
  file->end_effector.link = SourceName(r, r.Require(node, "link", "end_effector"), "end_effector.link");
  if (internal::YamlReader::Has(node, "point")) {
    file->end_effector.point_L = r.Vector3(node["point"], "end_effector.point", "m");
  }
  if (internal::YamlReader::Has(node, "controlled")) {
    const YAML::Node list = r.Sequence(node["controlled"], "end_effector.controlled", 6, "components");
    for (std::size_t i = 0; i < list.size(); ++i) {
      file->end_effector.controlled.push_back(r.Name(list[i], internal::Indexed("end_effector.controlled", i)));
    }
  }
}

// ccma's `q_home: {joint: q, ...}`: joint positions at home (rad or m).
void ReadPositions(const internal::YamlReader& r, const YAML::Node& root, ClosureFile* file) {
  if (!internal::YamlReader::Has(root, "q_home")) return;
  const YAML::Node map = r.Map(root["q_home"], "q_home");
  if (map.size() > kMaxClosureEntries) {
    r.Fail(map, "q_home", "more than " + std::to_string(kMaxClosureEntries) + " joints");
  }
  for (const auto& entry : map) {
    ClosureFile::Position position;
    position.joint = SourceName(r, entry.first, "q_home");
    position.q = r.Number(entry.second, "q_home[" + Quote(position.joint) + "]", "rad or m");
    position.line = entry.first.Mark().line + 1;
    file->positions.push_back(position);
  }
}

}  // namespace

ClosureFile ParseClosureFile(const std::string& text, const std::string& source) {
  if (text.size() > kMaxClosureFileBytes) throw ModelError(source + ": larger than 1 MiB (a closure file)");
  const YAML::Node root = internal::ParseYamlText(text, source);
  const internal::YamlReader r(source, nullptr, nullptr);
  ClosureFile file;
  file.source = source;
  if (!root.IsDefined() || root.IsNull()) return file;  // an empty file: no closures
  r.Map(root, "");
  try {
    ReadLoops(r, root, &file);
    ReadOffsets(r, root, &file);
    file.actuated = Names(r, root, "name_mot");
    if (internal::YamlReader::Has(root, "name_mot")) file.actuated_line = root["name_mot"].Mark().line + 1;
    ReadOverrides(r, root, &file);
    ReadEndEffector(r, root, &file);
    ReadPositions(r, root, &file);
    file.frames = Names(r, root, "frames");
    if (internal::YamlReader::Has(root, "frames")) file.frames_line = root["frames"].Mark().line + 1;
  } catch (const YAML::Exception& e) {  // a conversion we did not foresee
    throw ModelError(internal::WithLine(source, e.mark) + ": " + internal::LibraryMessage(e.msg));
  }
  return file;
}

ClosureFile ReadClosureFile(const std::string& path) {
  std::string text, error;
  if (!internal::ReadRegularFile(path, kMaxClosureFileBytes, "closure file", &text, &error)) throw ModelError(error);
  return ParseClosureFile(text, path);
}

}  // namespace ccma
